!> The sweep definition: the &sweep group read into a plan, its parameter sets and its
!> mode (src/sweep/sweep_mode.f90; one file per mode, made by
!> src/sweep/sweep_mode_factory.f90). What a job is: src/sweep/sweep_jobs.f90 and the
!> mode. The group's table and its read: src/sweep/sweep_group.f90.
module voussoir_sweep_plan
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa, int_list, fmt_exact_list, fmt_real, fmt_significant
  use voussoir_input_range, only: need
  use voussoir_config, only: config_t, config_entry_t, config_entries, config_to_nml, validate_config, &
                             arch_rule, arch_rule_text, has_loads, assembly_span
  use voussoir_sweep_group, only: sweep_group_t, read_sweep_group, lengths_text, n_kinds, param_kinds, list_names, &
                                  combine_paired, unset_real
  use voussoir_sweep_ida, only: n_sampled, range_names
  use voussoir_sweep_mode, only: sweep_mode_t, sweep_plan_t, set_description, job_param_set, run_bodies
  use voussoir_sweep_mode_factory, only: make_sweep_mode, default_mode
  use voussoir_assembly, only: assembly_t
  use voussoir_config_assembly, only: build_config_assembly
  use voussoir_placed_loads, only: placed_loads_t, place_loads
  implicit none
  private

  public :: sweep_plan_t, read_sweep_plan, set_description

  real(dp), parameter :: max_jobs = 1.0e7_dp
  !> Runs a threshold or ida search typically takes (the scan up, the refinement, the
  !> confirmations: 8 to 16 in the sweeps of docs/sweep.md); the master's first guess too.
  real(dp), parameter :: typical_search_runs = 12.0_dp
  character(len=*), parameter :: nl = achar(10)

contains

  !> Read and check the &sweep group of `path` against the base case `base`.
  subroutine read_sweep_plan(path, base, plan, status)
    character(len=*), intent(in) :: path
    type(config_t), intent(in) :: base
    type(sweep_plan_t), intent(out) :: plan
    type(status_t), intent(inout) :: status
    type(sweep_group_t), target :: group
    class(sweep_mode_t), allocatable :: mode
    logical :: drawn

    group%mode = default_mode
    call read_sweep_group(path, group, status)
    if (.not. status%ok) return
    if (base%solver%rest_capacity_m_s2 /= 0.0_dp) then
      call fail(status, path//': &solver rest_capacity_m_s2 is set, but a sweep sets it per model sample '// &
                '(&sweep skip_at_rest, modes ida and msa): remove it')
      return
    end if
    call make_sweep_mode(path, group%mode, mode, status)
    if (.not. status%ok) return
    call check_bridge_sweep(path, base, group, mode, status)
    if (.not. status%ok) return
    plan%combine = group%combine
    plan%pair_frequencies = group%pair_frequencies
    call mode%check_settings(group, base, path, plan, status)
    if (.not. status%ok) return
    plan%progress_every_s = group%progress_every_s

    call check_lists(path, base, group, plan%combine, status)
    if (.not. status%ok) return
    call mode%draw_sets(group, base, path, group%lengths, plan, drawn, status)
    if (.not. status%ok) return
    if (.not. drawn) call build_sets(path, base, group%lists, group%lengths, plan, status)
    if (.not. status%ok) return
    call mode%prepare_sets(group, plan, status)
    if (.not. status%ok) return
    if (plan%pair_frequencies .and. plan%n_freq /= plan%n_sets) then
      call fail(status, path//': &sweep pair_frequencies = .true. needs one frequency per parameter set: '// &
                'frequencies_hz has '//itoa(plan%n_freq)//' entries, the lists give '//itoa(plan%n_sets)//' sets')
      return
    end if
    if (real(plan%n_sets, dp)*plan%n_freq_per_set*plan%n_amp > max_jobs) then
      call fail(status, path//': the sweep has more than 1e7 jobs; split it')
      return
    end if
    plan%n_jobs = plan%n_sets*plan%n_freq_per_set*plan%n_amp
    call check_loads_placed(path, plan, status)
    call check_amplitudes_span(path, group, plan, status)
    if (.not. status%ok) return
    call make_texts(mode, base, group%lists, group%lengths, plan)
    call move_alloc(mode, plan%mode)
    call estimate_cost(path, group%max_runs, plan, status)
  end subroutine read_sweep_plan

  !> What a sweep of a &bridge (docs/bridges.md, "The bridge under earthquakes") cannot
  !> take: the lists and the model samples set &arch variables, which a bridge does not
  !> read (its parts carry their own friction, density and ring); and a mode that says
  !> why it cannot (bridge_refusal).
  subroutine check_bridge_sweep(path, base, group, mode, status)
    character(len=*), intent(in) :: path
    type(config_t), intent(in) :: base
    type(sweep_group_t), intent(in) :: group
    class(sweep_mode_t), intent(in) :: mode
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: why
    integer :: j
    if (base%bridge%n_spans == 0) return
    why = mode%bridge_refusal()
    if (len(why) > 0) then
      call fail(status, path//": &sweep mode = '"//trim(mode%name)//"' is refused with &bridge: "//why// &
                "; use mode = 'threshold', 'grid' or 'ida'")
      return
    end if
    do j = 1, n_kinds
      if (group%lengths(j) == 0) cycle
      call fail(status, path//': &sweep '//trim(list_names(j))//' is refused with &bridge: the swept lists set '// &
                '&arch variables ('//trim(param_kinds(j))//'), which a bridge does not read (its parts carry '// &
                'their own ring, density and friction in &bridge); sweep one bridge per input file')
      return
    end do
    do j = 1, n_sampled
      if (all(group%ranges(:, j) == unset_real)) cycle
      call fail(status, path//': &sweep '//trim(range_names(j))//' is refused with &bridge: the model samples '// &
                'set &arch variables, which a bridge does not read; leave out n_samples and the ranges')
      return
    end do
    if (len_trim(group%model_samples_file) > 0) &
      call fail(status, path//': &sweep model_samples_file is refused with &bridge: its samples set &arch '// &
                'variables relative to a nominal arch, which a bridge does not read')
  end subroutine check_bridge_sweep

  !> Every load of &load on a block of every parameter set's assembly, where a run puts
  !> it (before any run, rather than a failed run per job).
  subroutine check_loads_placed(path, plan, status)
    character(len=*), intent(in) :: path
    type(sweep_plan_t), intent(in) :: plan
    type(status_t), intent(inout) :: status
    type(assembly_t) :: asm
    type(placed_loads_t) :: placed
    integer :: s
    do s = 0, plan%n_sets - 1
      if (.not. has_loads(plan%set_cfg(s))) cycle
      call build_config_assembly(plan%set_cfg(s), asm, status)
      if (status%ok) call place_loads(plan%set_cfg(s)%load, asm, 0.0_dp, placed, status)
      if (.not. status%ok) then
        if (plan%n_sets > 1) status%message = trim(status%message)//' (parameter set '//itoa(s)//')'
        status%message = path//': '//trim(status%message)
        return
      end if
    end do
  end subroutine check_loads_placed

  !> The grid's amplitudes (&sweep amplitudes_m; no other mode takes them) against the
  !> assembly of every parameter set, as config_plausible.f90 checks &motion amplitude_m:
  !> an amplitude larger than the arch's span is a slip of units (millimetres as metres).
  subroutine check_amplitudes_span(path, group, plan, status)
    character(len=*), intent(in) :: path
    type(sweep_group_t), intent(in) :: group
    type(sweep_plan_t), intent(in) :: plan
    type(status_t), intent(inout) :: status
    real(dp) :: span_m
    character(len=:), allocatable :: what, hint, of_set
    integer :: s, k
    if (.not. status%ok) return
    do s = 0, plan%n_sets - 1
      call assembly_span(plan%set_cfg(s), span_m, what)
      if (span_m <= 0.0_dp) cycle
      do k = 1, group%n_amplitudes
        associate (a => group%amplitudes_m(k))
          if (a <= span_m) cycle
          hint = ''
          if (a >= 1.0_dp .and. a/1000.0_dp <= span_m) &
            hint = ': did you mean millimetres ('//fmt_significant(a/1000.0_dp, 4)//' m)?'
          of_set = ''
          if (plan%n_sets > 1) of_set = ' of parameter set '//itoa(s)//' ('//set_description(plan, s)//')'
          call fail(status, path//': &sweep amplitudes_m('//itoa(k)//') = '//fmt_real(a)//' m is larger than '// &
                    what//of_set//' ('//fmt_significant(span_m, 3)//' m; allowed: amplitudes_m <= '// &
                    fmt_significant(span_m, 3)//' m)'//hint)
          return
        end associate
      end do
    end do
  end subroutine check_amplitudes_span

  !> The plan's cost (its runs, simulated seconds and steps x blocks; voussoir-sweep
  !> prints them before it starts), and the cap on its runs, &sweep max_runs: a grid job
  !> is one run, a search is counted at `typical_search_runs`.
  subroutine estimate_cost(path, max_runs, plan, status)
    character(len=*), intent(in) :: path
    integer, intent(in) :: max_runs
    type(sweep_plan_t), intent(inout) :: plan
    type(status_t), intent(inout) :: status
    real(dp) :: per_job, cost
    integer :: job
    character(len=:), allocatable :: counted, about
    per_job = 1.0_dp
    counted = ''
    about = ''
    if (plan%mode%has_search()) then
      per_job = typical_search_runs
      counted = ': searches of about '//itoa(nint(typical_search_runs))//' runs each'
      about = 'about '
    end if
    plan%est_runs = per_job*plan%n_jobs
    if (plan%est_runs > max_runs) then
      call fail(status, path//': the sweep would take '//about// &
                itoa(nint(plan%est_runs))//' runs ('//itoa(plan%n_jobs)//' jobs'//counted//'): more than '// &
                '&sweep max_runs = '//itoa(max_runs)//'; split the sweep or raise max_runs')
      return
    end if
    plan%est_simulated_s = 0.0_dp
    plan%est_step_blocks = 0.0_dp
    do job = 0, plan%n_jobs - 1
      cost = plan%mode%cost(plan, job)   ! steps x bodies (run_bodies: the mode's cost)
      plan%est_step_blocks = plan%est_step_blocks + per_job*cost
      associate (c => plan%set_cfg(job_param_set(plan, job)))
        plan%est_simulated_s = plan%est_simulated_s + per_job*cost*c%solver%dt_s/run_bodies(c)
      end associate
    end do
  end subroutine estimate_cost

  !> The swept lists (`group%lengths`: entries of each): each entry in the range &arch
  !> allows (what depends on other variables is checked on each set's whole case), arch
  !> lists only for arches, equal lengths when paired.
  subroutine check_lists(path, base, group, combine, status)
    character(len=*), intent(in) :: path, combine
    type(config_t), intent(in) :: base
    type(sweep_group_t), intent(in) :: group
    type(status_t), intent(inout) :: status
    integer :: j, k
    do j = 1, n_kinds
      do k = 1, group%lengths(j)
        call need(arch_rule(param_kinds(j), group%lists(k, j)), path, 'sweep', trim(list_names(j))//'('//itoa(k)// &
                  ')', group%lists(k, j), arch_rule_text(param_kinds(j)), status)
      end do
    end do
    if (.not. status%ok) return
    if (len_trim(base%arch%polygon_file) > 0 .and. any(group%lengths(1:3) > 0)) then
      call fail(status, path//': &sweep embrace_list_deg, n_voussoirs_list and thickness_list_m apply to '// &
                'arches, but &arch polygon_file is set')
      return
    end if
    if (combine == combine_paired .and. count(group%lengths > 0) > 1) then
      if (any(group%lengths > 0 .and. group%lengths /= maxval(group%lengths))) then
        call fail(status, path//": &sweep combine = '"//combine_paired//"' needs swept lists of equal length; "// &
                  'they have '//lengths_text(group%lengths))
        return
      end if
    end if
  end subroutine check_lists

  !> The parameter sets of the lists (the first swept parameter varies slowest, or entry
  !> k of every list with combine = 'paired') and their validated cases.
  subroutine build_sets(path, base, lists, lengths, plan, status)
    character(len=*), intent(in) :: path
    type(config_t), intent(in) :: base
    real(dp), intent(in) :: lists(:, :)
    integer, intent(in) :: lengths(:)
    type(sweep_plan_t), intent(inout) :: plan
    type(status_t), intent(inout) :: status
    integer :: s, j, p, rest, pick(n_kinds)
    type(status_t) :: check
    character(len=:), allocatable :: inner
    plan%n_params = count(lengths > 0)
    plan%param_names = pack(param_kinds, lengths > 0)
    if (plan%n_params == 0) then
      plan%n_sets = 1
    else if (plan%combine == combine_paired) then
      plan%n_sets = maxval(lengths)
    else
      plan%n_sets = product(pack(lengths, lengths > 0))
    end if
    allocate (plan%param_values(plan%n_params, plan%n_sets), plan%set_cfg(0:plan%n_sets - 1))
    do s = 0, plan%n_sets - 1
      rest = s
      do j = n_kinds, 1, -1
        pick(j) = 0
        if (lengths(j) == 0) cycle
        if (plan%combine == combine_paired) then
          pick(j) = s + 1
        else
          pick(j) = modulo(rest, lengths(j)) + 1
          rest = rest/lengths(j)
        end if
      end do
      p = 0
      plan%set_cfg(s) = base
      do j = 1, n_kinds
        if (lengths(j) == 0) cycle
        p = p + 1
        plan%param_values(p, s + 1) = lists(pick(j), j)
        call set_arch_value(plan%set_cfg(s), j, lists(pick(j), j))
      end do
      call validate_config(plan%set_cfg(s), check)
      if (.not. check%ok) then
        inner = trim(check%message)
        if (index(inner, path//': ') == 1) inner = inner(len(path) + 3:)
        call fail(status, path//': &sweep parameter set '//itoa(s)//' ('//set_description(plan, s)// &
                  '): '//inner)
        return
      end if
    end do
  end subroutine build_sets

  !> Set swept parameter `kind` (the order of param_kinds) of the &arch of `cfg`.
  pure subroutine set_arch_value(cfg, kind, value)
    type(config_t), intent(inout) :: cfg
    integer, intent(in) :: kind
    real(dp), intent(in) :: value
    select case (kind)
    case (1)
      cfg%arch%embrace_deg = value
    case (2)
      cfg%arch%n_voussoirs = nint(value)
    case (3)
      cfg%arch%thickness_m = value
    case (4)
      cfg%arch%friction = value
    case (5)
      cfg%arch%contact_inset_m = value
    end select
  end subroutine set_arch_value

  !> The effective &sweep group and the signature of the sweep definition.
  subroutine make_texts(mode, base, lists, lengths, plan)
    class(sweep_mode_t), intent(in) :: mode
    type(config_t), intent(in) :: base
    real(dp), intent(in) :: lists(:, :)
    integer, intent(in) :: lengths(:)
    type(sweep_plan_t), intent(inout) :: plan
    character(len=:), allocatable :: body
    type(config_entry_t), allocatable :: e(:)
    integer :: j
    body = "&sweep"//nl//"  mode = '"//trim(mode%name)//"'"//nl// &
           "  combine = '"//trim(plan%combine)//"'"//nl// &
           '  pair_frequencies = '//trim(merge('.true. ', '.false.', plan%pair_frequencies))//nl// &
           mode%settings_text(plan)
    do j = 1, n_kinds
      if (lengths(j) == 0) cycle
      if (j == 2) then
        body = body//'  '//trim(list_names(j))//' = '//int_list(nint(lists(1:lengths(j), j)))//nl
      else
        body = body//'  '//trim(list_names(j))//' = '//fmt_exact_list(lists(1:lengths(j), j))//nl
      end if
    end do
    plan%sweep_nml = body//'  progress_every_s = '//fmt_exact_list([plan%progress_every_s])//nl//'/'//nl
    ! The base case without what does not change results (file name, sampling), nor the
    ! steps at rest, always 0 in a sweep's base (read_sweep_plan): files of the code before
    ! it was a &solver variable stay the same sweep.
    e = config_entries(base)
    e = pack(e, .not. (e%group == 'output' .and. (e%name == 'file' .or. e%name == 'every')) .and. &
             .not. (e%group == 'solver' .and. e%name == 'rest_capacity_m_s2'))
    plan%signature = 'voussoir-sweep definition'//nl//body//'/'//nl//mode%definition_text(plan)//config_to_nml(e)
  end subroutine make_texts

end module voussoir_sweep_plan
