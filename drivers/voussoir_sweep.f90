!> voussoir-sweep FILE.nml: many simulations of one base case, spread over MPI ranks.
!>
!> `mpirun -np N voussoir-sweep FILE.nml`. The &arch, &motion, &solver and &output groups
!> give the base case as for voussoir-run; &sweep says what varies (docs/sweep.md):
!> mode 'threshold' finds the collapse threshold amplitude at each frequency, mode 'grid'
!> runs every frequency x amplitude; optional lists over model parameters make parameter
!> sets (Cartesian product or paired). Rank 0 writes &output's `file` (HDF5, always
!> whole) and a CSV summary beside it, and resumes from that file when rerun.
!>
!> Three small modules precede the program: the sweep definition (no MPI), the MPI
!> layer, and the master and worker roles.

!> The sweep definition: the &sweep group, its parameter sets and its jobs.
module voussoir_sweep_plan
  use, intrinsic :: iso_fortran_env, only: iostat_end
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: lower, itoa, int_list
  use voussoir_config, only: config_t, config_entry_t, config_entries, config_to_nml, validate_config, &
                             fmt_real
  use voussoir_threshold, only: threshold_settings_t, search_run_config
  implicit none
  private

  public :: sweep_plan_t, read_sweep_plan, job_param_set, job_frequency_hz, job_amplitude_m, &
            job_run_config, job_cost, set_description

  integer, parameter :: max_list = 256              !! entries of every &sweep list
  real(dp), parameter :: unset_real = -huge(1.0_dp) !! sentinel of an unset list entry
  integer, parameter :: unset_int = -huge(1)
  real(dp), parameter :: max_jobs = 1.0e7_dp
  integer, parameter :: n_kinds = 5                 !! model parameters that can be swept
  character(len=*), parameter :: nl = achar(10)
  !> Swept parameters in the order of their columns, and their &sweep list names.
  character(len=16), parameter :: param_kinds(n_kinds) = [character(len=16) :: &
    'embrace_deg', 'n_voussoirs', 'thickness_m', 'friction', 'contact_inset_m']
  character(len=24), parameter :: list_names(n_kinds) = [character(len=24) :: &
    'embrace_list_deg', 'n_voussoirs_list', 'thickness_list_m', 'friction_list', 'contact_inset_list_m']

  !> Everything a rank needs to turn a job index into a run.
  type :: sweep_plan_t
    character(len=16) :: mode = 'threshold'       !! threshold or grid
    character(len=16) :: combine = 'product'      !! product or paired
    logical :: pair_frequencies = .false.         !! frequency k goes with parameter set k only
    real(dp), allocatable :: frequencies_hz(:)
    real(dp), allocatable :: amplitudes_m(:)      !! grid mode
    type(threshold_settings_t) :: search          !! threshold mode
    real(dp) :: progress_every_s = 10.0_dp        !! seconds between progress lines
    integer :: n_params = 0, n_sets = 1, n_freq = 0, n_amp = 1, n_jobs = 0
    integer :: n_freq_per_set = 0                 !! n_freq, or 1 with pair_frequencies
    character(len=16), allocatable :: param_names(:)
    real(dp), allocatable :: param_values(:, :)   !! (n_params, n_sets)
    type(config_t), allocatable :: set_cfg(:)     !! (0:n_sets-1) the validated case of each set
    character(len=:), allocatable :: sweep_nml    !! the effective &sweep group
    character(len=:), allocatable :: signature    !! what a resumed file must match
  end type sweep_plan_t

contains

  !> Read and check the &sweep group of `path` against the base case `base`.
  subroutine read_sweep_plan(path, base, plan, status)
    character(len=*), intent(in) :: path
    type(config_t), intent(in) :: base
    type(sweep_plan_t), intent(out) :: plan
    type(status_t), intent(inout) :: status
    character(len=16) :: mode, combine
    logical :: pair_frequencies
    real(dp) :: frequencies_hz(max_list), amplitudes_m(max_list)
    real(dp) :: amp_tol_m, amp_max_m, scan_step, progress_every_s
    integer :: refine_factor, n_confirm
    real(dp) :: embrace_list_deg(max_list), thickness_list_m(max_list), friction_list(max_list), &
                contact_inset_list_m(max_list)
    integer :: n_voussoirs_list(max_list)
    namelist /sweep/ mode, combine, pair_frequencies, frequencies_hz, amplitudes_m, amp_tol_m, amp_max_m, scan_step, &
      refine_factor, n_confirm, progress_every_s, embrace_list_deg, n_voussoirs_list, thickness_list_m, &
      friction_list, contact_inset_list_m
    type(threshold_settings_t) :: defaults
    real(dp) :: lists(max_list, n_kinds), f_max_hz
    integer :: lengths(n_kinds), unit, ios, k, n_freq, n_amp
    character(len=512) :: iomsg

    mode = plan%mode
    combine = plan%combine
    pair_frequencies = plan%pair_frequencies
    frequencies_hz = unset_real
    amplitudes_m = unset_real
    amp_tol_m = defaults%amp_tol_m
    amp_max_m = defaults%amp_max_m
    scan_step = defaults%scan_step
    refine_factor = defaults%refine_factor
    n_confirm = defaults%n_confirm
    progress_every_s = plan%progress_every_s
    embrace_list_deg = unset_real
    thickness_list_m = unset_real
    friction_list = unset_real
    contact_inset_list_m = unset_real
    n_voussoirs_list = unset_int

    call check_names(path, 'sweep', [character(len=24) :: 'mode', 'combine', 'pair_frequencies', &
      'frequencies_hz', 'amplitudes_m', 'amp_tol_m', 'amp_max_m', 'scan_step', 'refine_factor', 'n_confirm', &
      'progress_every_s', list_names], status)
    if (.not. status%ok) return
    open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      call fail(status, path//': cannot open input: '//trim(iomsg))
      return
    end if
    read (unit, nml=sweep, iostat=ios, iomsg=iomsg)
    close (unit)
    if (ios == iostat_end) then
      call fail(status, path//': no &sweep group; voussoir-sweep needs one (mode, frequencies_hz, ...; '// &
                'see docs/sweep.md)')
      return
    else if (ios /= 0) then
      call fail(status, path//': in namelist group &sweep: '//trim(iomsg))
      return
    end if

    plan%mode = lower(mode)
    plan%combine = lower(combine)
    select case (plan%mode)
    case ('threshold', 'grid')
    case default
      call fail(status, path//": &sweep mode = '"//trim(mode)//"' is not one of 'threshold', 'grid'")
      return
    end select
    select case (plan%combine)
    case ('product', 'paired')
    case default
      call fail(status, path//": &sweep combine = '"//trim(combine)//"' is not one of 'product', 'paired'")
      return
    end select
    if (base%motion%waveform /= 'afd') then
      call fail(status, path//": &motion waveform = '"//trim(base%motion%waveform)// &
                "': a sweep sets the frequency and amplitude of the 'afd' waveform; use waveform = 'afd'")
      return
    end if

    ! Frequencies: at least one, each resolved by at least 20 steps per cycle.
    n_freq = list_length(frequencies_hz, 'frequencies_hz')
    if (.not. status%ok) return
    if (n_freq == 0) then
      call fail(status, path//': &sweep frequencies_hz is not set: give at least one frequency')
      return
    end if
    f_max_hz = 1.0_dp/(20.0_dp*base%solver%dt_s)
    do k = 1, n_freq
      call need(frequencies_hz(k) > 0.0_dp .and. frequencies_hz(k) <= f_max_hz, 'frequencies_hz', k, &
                frequencies_hz(k), '0 < frequencies_hz <= 1/(20 dt_s) = '//fmt_real(f_max_hz))
    end do
    n_amp = list_length(amplitudes_m, 'amplitudes_m')
    if (.not. status%ok) return
    if (plan%mode == 'grid') then
      if (n_amp == 0) then
        call fail(status, path//": &sweep amplitudes_m is not set: mode = 'grid' needs at least one amplitude")
        return
      end if
      do k = 1, n_amp
        call need(amplitudes_m(k) >= 0.0_dp, 'amplitudes_m', k, amplitudes_m(k), 'amplitudes_m >= 0')
      end do
    else
      if (n_amp > 0) then
        call fail(status, path//": &sweep amplitudes_m is set but mode = 'threshold' searches the "// &
                  "amplitude: remove amplitudes_m or use mode = 'grid'")
        return
      end if
      n_amp = 1
      call need(amp_tol_m > 0.0_dp, 'amp_tol_m', 0, amp_tol_m, 'amp_tol_m > 0')
      call need(amp_max_m > amp_tol_m, 'amp_max_m', 0, amp_max_m, 'amp_max_m > amp_tol_m = '//fmt_real(amp_tol_m))
      call need(scan_step > 0.0_dp .and. scan_step <= 1.0_dp, 'scan_step', 0, scan_step, '0 < scan_step <= 1')
      call need(refine_factor >= 2 .and. refine_factor <= 64, 'refine_factor', 0, real(refine_factor, dp), &
                '2 <= refine_factor <= 64 (2: bisection)')
      call need(n_confirm >= 0 .and. n_confirm <= 16, 'n_confirm', 0, real(n_confirm, dp), '0 <= n_confirm <= 16')
    end if
    call need(progress_every_s >= 0.0_dp, 'progress_every_s', 0, progress_every_s, &
              'progress_every_s >= 0 (0: every result)')
    if (.not. status%ok) return

    ! Parameter lists.
    lists(:, 1) = embrace_list_deg
    lists(:, 2) = merge(real(n_voussoirs_list, dp), unset_real, n_voussoirs_list /= unset_int)
    lists(:, 3) = thickness_list_m
    lists(:, 4) = friction_list
    lists(:, 5) = contact_inset_list_m
    do k = 1, n_kinds
      lengths(k) = list_length(lists(:, k), trim(list_names(k)))
    end do
    if (.not. status%ok) return
    do k = 1, lengths(1)
      call need(lists(k, 1) > 0.0_dp .and. lists(k, 1) <= 180.0_dp, 'embrace_list_deg', k, lists(k, 1), &
                '0 < embrace_deg <= 180')
    end do
    do k = 1, lengths(2)
      call need(n_voussoirs_list(k) >= 3 .and. n_voussoirs_list(k) <= 1000, 'n_voussoirs_list', k, lists(k, 2), &
                '3 <= n_voussoirs <= 1000')
    end do
    do k = 1, lengths(3)
      call need(lists(k, 3) > 0.0_dp, 'thickness_list_m', k, lists(k, 3), 'thickness_m > 0')
    end do
    do k = 1, lengths(4)
      call need(lists(k, 4) >= 0.0_dp, 'friction_list', k, lists(k, 4), 'friction >= 0')
    end do
    do k = 1, lengths(5)
      call need(lists(k, 5) >= 0.0_dp, 'contact_inset_list_m', k, lists(k, 5), 'contact_inset_m >= 0')
    end do
    if (.not. status%ok) return
    if (len_trim(base%arch%polygon_file) > 0 .and. any(lengths(1:3) > 0)) then
      call fail(status, path//': &sweep embrace_list_deg, n_voussoirs_list and thickness_list_m apply to '// &
                'arches, but &arch polygon_file is set')
      return
    end if
    if (plan%combine == 'paired' .and. count(lengths > 0) > 1) then
      if (any(lengths > 0 .and. lengths /= maxval(lengths))) then
        call fail(status, path//": &sweep combine = 'paired' needs swept lists of equal length; they have "// &
                  lengths_text(lengths))
        return
      end if
    end if

    plan%frequencies_hz = frequencies_hz(1:n_freq)
    plan%n_freq = n_freq
    plan%pair_frequencies = pair_frequencies
    plan%n_freq_per_set = merge(1, n_freq, pair_frequencies)
    plan%n_amp = n_amp
    if (plan%mode == 'grid') then
      plan%amplitudes_m = amplitudes_m(1:n_amp)
    else
      allocate (plan%amplitudes_m(0))
    end if
    plan%search%amp_tol_m = amp_tol_m
    plan%search%amp_max_m = amp_max_m
    plan%search%scan_step = scan_step
    plan%search%refine_factor = refine_factor
    plan%search%n_confirm = n_confirm
    plan%progress_every_s = progress_every_s

    call build_sets(lists, lengths)
    if (.not. status%ok) return
    if (pair_frequencies .and. n_freq /= plan%n_sets) then
      call fail(status, path//': &sweep pair_frequencies = .true. needs one frequency per parameter set: '// &
                'frequencies_hz has '//itoa(n_freq)//' entries, the lists give '//itoa(plan%n_sets)//' sets')
      return
    end if
    if (real(plan%n_sets, dp)*plan%n_freq_per_set*plan%n_amp > max_jobs) then
      call fail(status, path//': the sweep has more than 1e7 jobs; split it')
      return
    end if
    plan%n_jobs = plan%n_sets*plan%n_freq_per_set*plan%n_amp
    call make_texts(lists, lengths)

  contains

    !> Entries set from the start of `x`, with no gap.
    integer function list_length(x, name) result(n)
      real(dp), intent(in) :: x(:)
      character(len=*), intent(in) :: name
      integer :: j
      character(len=16) :: a, b
      n = 0
      do j = 1, size(x)
        if (x(j) == unset_real) exit
        n = j
      end do
      do j = n + 2, size(x)
        if (x(j) /= unset_real .and. status%ok) then
          write (a, '(i0)') n + 1
          write (b, '(i0)') j
          call fail(status, path//': &sweep '//name//'('//trim(a)//') is unset but '//name//'('//trim(b)// &
                    ') = '//fmt_real(x(j))//' is set: give the list without gaps')
        end if
      end do
    end function list_length

    subroutine need(good, name, index, value, allowed)
      logical, intent(in) :: good
      character(len=*), intent(in) :: name, allowed
      integer, intent(in) :: index
      real(dp), intent(in) :: value
      character(len=16) :: idx
      if (good .or. .not. status%ok) return
      idx = ''
      if (index > 0) write (idx, '(a,i0,a)') '(', index, ')'
      call fail(status, path//': &sweep '//name//trim(idx)//' = '//fmt_real(value)// &
                ' is outside the allowed range '//allowed)
    end subroutine need

    function lengths_text(n) result(text)
      integer, intent(in) :: n(:)
      character(len=:), allocatable :: text
      character(len=16) :: buf
      integer :: j
      text = ''
      do j = 1, size(n)
        if (n(j) == 0) cycle
        write (buf, '(i0)') n(j)
        if (len(text) > 0) text = text//', '
        text = text//trim(list_names(j))//' '//trim(buf)
      end do
    end function lengths_text

    !> The parameter sets (the first swept parameter varies slowest) and their cases.
    subroutine build_sets(lists, lengths)
      real(dp), intent(in) :: lists(:, :)
      integer, intent(in) :: lengths(:)
      integer :: s, j, p, rest, pick(n_kinds)
      type(status_t) :: check
      character(len=:), allocatable :: inner
      plan%n_params = count(lengths > 0)
      plan%param_names = pack(param_kinds, lengths > 0)
      if (plan%n_params == 0) then
        plan%n_sets = 1
      else if (plan%combine == 'paired') then
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
          if (plan%combine == 'paired') then
            pick(j) = s + 1
          else
            pick(j) = modulo(rest, lengths(j)) + 1
            rest = rest/lengths(j)
          end if
        end do
        p = 0
        plan%set_cfg(s) = base
        associate (a => plan%set_cfg(s)%arch)
          do j = 1, n_kinds
            if (lengths(j) == 0) cycle
            p = p + 1
            plan%param_values(p, s + 1) = lists(pick(j), j)
            select case (j)
            case (1)
              a%embrace_deg = lists(pick(j), j)
            case (2)
              a%n_voussoirs = nint(lists(pick(j), j))
            case (3)
              a%thickness_m = lists(pick(j), j)
            case (4)
              a%friction = lists(pick(j), j)
            case (5)
              a%contact_inset_m = lists(pick(j), j)
            end select
          end do
        end associate
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

    !> The effective &sweep group and the signature of the sweep definition.
    subroutine make_texts(lists, lengths)
      real(dp), intent(in) :: lists(:, :)
      integer, intent(in) :: lengths(:)
      character(len=:), allocatable :: body
      type(config_entry_t), allocatable :: e(:)
      integer :: j
      body = "&sweep"//nl//"  mode = '"//trim(plan%mode)//"'"//nl// &
             "  combine = '"//trim(plan%combine)//"'"//nl// &
             '  pair_frequencies = '//trim(merge('.true. ', '.false.', plan%pair_frequencies))//nl// &
             '  frequencies_hz = '//real_list(plan%frequencies_hz)//nl
      if (plan%mode == 'grid') then
        body = body//'  amplitudes_m = '//real_list(plan%amplitudes_m)//nl
      else
        body = body//'  amp_tol_m = '//real_list([plan%search%amp_tol_m])//nl// &
               '  amp_max_m = '//real_list([plan%search%amp_max_m])//nl// &
               '  scan_step = '//real_list([plan%search%scan_step])//nl// &
               '  refine_factor = '//itoa(plan%search%refine_factor)//nl// &
               '  n_confirm = '//itoa(plan%search%n_confirm)//nl
      end if
      do j = 1, n_kinds
        if (lengths(j) == 0) cycle
        if (j == 2) then
          body = body//'  '//trim(list_names(j))//' = '//int_list(nint(lists(1:lengths(j), j)))//nl
        else
          body = body//'  '//trim(list_names(j))//' = '//real_list(lists(1:lengths(j), j))//nl
        end if
      end do
      plan%sweep_nml = body//'  progress_every_s = '//real_list([plan%progress_every_s])//nl//'/'//nl
      ! The base case without what does not change results (file name, sampling).
      e = config_entries(base)
      e = pack(e, .not. (e%group == 'output' .and. (e%name == 'file' .or. e%name == 'every')))
      plan%signature = 'voussoir-sweep definition'//nl//body//'/'//nl//config_to_nml(e)
    end subroutine make_texts

  end subroutine read_sweep_plan

  !> Fail on a variable of namelist group `group` in `path` that is not in `known`: the
  !> compiler's own message for it names another variable.
  subroutine check_names(path, group, known, status)
    character(len=*), intent(in) :: path, group
    character(len=*), intent(in) :: known(:)
    type(status_t), intent(inout) :: status
    character(len=1024) :: line
    character(len=:), allocatable :: text, name
    character(len=1) :: quote
    integer :: unit, ios, i, j, k
    logical :: inside

    open (newunit=unit, file=path, status='old', action='read', iostat=ios)
    if (ios /= 0) return   ! reported by the namelist read
    text = ''
    inside = .false.
    quote = ' '
    do
      read (unit, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (.not. inside) then
        line = adjustl(line)
        if (lower(line(1:len(group) + 1)) /= '&'//group .or. &
            verify(line(len(group) + 2:len(group) + 2), ' ,/!'//achar(9)) /= 0) cycle
        inside = .true.
        line = line(len(group) + 2:)
      end if
      ! Keep the group's text up to its closing '/', without comments and quoted text.
      do i = 1, len_trim(line)
        if (quote /= ' ') then
          if (line(i:i) == quote) quote = ' '
          cycle
        end if
        select case (line(i:i))
        case ("'", '"')
          quote = line(i:i)
          text = text//' '
        case ('!')
          exit
        case ('/')
          inside = .false.
          exit
        case default
          text = text//line(i:i)
        end select
      end do
      if (.not. inside .and. len(text) > 0) exit
      text = text//' '
    end do
    close (unit)
    ! A name is the identifier before each '=' (after an optional (index)).
    do k = 1, len(text)
      if (text(k:k) /= '=') cycle
      j = k - 1
      do while (j > 0)
        if (text(j:j) /= ' ') exit
        j = j - 1
      end do
      if (j > 0) then
        if (text(j:j) == ')') then
          j = index(text(1:j), '(', back=.true.) - 1
          do while (j > 0)
            if (text(j:j) /= ' ') exit
            j = j - 1
          end do
        end if
      end if
      i = j
      do while (i > 0)
        if (verify(lower(text(i:i)), 'abcdefghijklmnopqrstuvwxyz0123456789_') /= 0) exit
        i = i - 1
      end do
      if (j <= i) cycle
      name = lower(text(i + 1:j))
      if (.not. any(known == name)) then
        call fail(status, path//': &'//group//" has no variable '"//name//"' (known: "// &
                  join_names(known)//')')
        return
      end if
    end do
  contains
    function join_names(names) result(list)
      character(len=*), intent(in) :: names(:)
      character(len=:), allocatable :: list
      integer :: n
      list = trim(names(1))
      do n = 2, size(names)
        list = list//', '//trim(names(n))
      end do
    end function join_names
  end subroutine check_names

  !> "name = value, ..." of parameter set `s` (0-based), or "base case".
  function set_description(plan, s) result(text)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: s
    character(len=:), allocatable :: text
    integer :: p
    text = ''
    do p = 1, plan%n_params
      if (p > 1) text = text//', '
      text = text//trim(plan%param_names(p))//' = '//fmt_real(plan%param_values(p, s + 1))
    end do
    if (plan%n_params == 0) text = 'base case'
  end function set_description

  !> Parameter set (0-based) of job `job` (0-based).
  pure integer function job_param_set(plan, job)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    job_param_set = job/(plan%n_freq_per_set*plan%n_amp)
  end function job_param_set

  pure real(dp) function job_frequency_hz(plan, job)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    if (plan%pair_frequencies) then
      job_frequency_hz = plan%frequencies_hz(job_param_set(plan, job) + 1)
    else
      job_frequency_hz = plan%frequencies_hz(modulo(job/plan%n_amp, plan%n_freq) + 1)
    end if
  end function job_frequency_hz

  !> Commanded amplitude of a grid job (0 in threshold mode).
  pure real(dp) function job_amplitude_m(plan, job)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    job_amplitude_m = 0.0_dp
    if (plan%mode == 'grid') job_amplitude_m = plan%amplitudes_m(modulo(job, plan%n_amp) + 1)
  end function job_amplitude_m

  !> The configuration of one run of job `job` at `amplitude_m`: a threshold search run
  !> stops at the collapse; a grid run keeps the base case's stop_after_collapse_s. No
  !> time series is kept.
  pure function job_run_config(plan, job, amplitude_m) result(cfg)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    real(dp), intent(in) :: amplitude_m
    type(config_t) :: cfg
    cfg = search_run_config(plan%set_cfg(job_param_set(plan, job)), job_frequency_hz(plan, job), amplitude_m)
    if (plan%mode == 'grid') cfg%output%stop_after_collapse_s = &
      plan%set_cfg(job_param_set(plan, job))%output%stop_after_collapse_s
  end function job_run_config

  !> Relative cost of one run of job `job`: steps x bodies.
  pure real(dp) function job_cost(plan, job)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    real(dp) :: duration_s, f_hz
    f_hz = job_frequency_hz(plan, job)
    associate (c => plan%set_cfg(job_param_set(plan, job)))
      duration_s = c%motion%duration_s
      if (duration_s == 0.0_dp) duration_s = (c%motion%n_attack + c%motion%n_full + c%motion%n_decay)/f_hz &
                                             + c%motion%rest_s
      job_cost = duration_s/c%solver%dt_s*(c%arch%n_voussoirs + 2)
    end associate
  end function job_cost



  !> Reals written so that they read back exactly.
  function real_list(x) result(text)
    real(dp), intent(in) :: x(:)
    character(len=:), allocatable :: text
    character(len=32) :: buf
    integer :: j
    text = ''
    do j = 1, size(x)
      write (buf, '(es24.16)') x(j)
      if (j > 1) text = text//', '
      text = text//trim(adjustl(buf))
    end do
  end function real_list


end module voussoir_sweep_plan

!> The MPI layer of the sweep: a duplicated communicator and short messages of reals.
!>
!> Sends are nonblocking (MPI_Isend from a fixed pool of buffers that MPI owns until the
!> send completes), so no rank ever waits for a receiver: rank 0 can answer while it
!> computes and no order of sends can deadlock. An idle rank polls (MPI_Iprobe) and
!> sleeps 1 ms between polls instead of spinning in a blocking receive, which would
!> take a core from the ranks that compute when the machine is oversubscribed.
module voussoir_sweep_comm
  use, intrinsic :: iso_c_binding, only: c_int
  use, intrinsic :: iso_fortran_env, only: output_unit
  use mpi_f08
  use voussoir_kinds, only: dp
  implicit none
  private

  public :: sweep_comm_t, comm_start, comm_end, comm_abort, comm_agree, comm_send, comm_poll, &
            comm_recv, wall_s, nap
  public :: tag_task, tag_result, tag_stop

  integer, parameter :: tag_task = 1, tag_result = 2, tag_stop = 3
  integer, parameter :: nap_us = 1000                      !! poll interval of an idle rank [us]

  !> This rank in the sweep's communicator.
  type :: sweep_comm_t
    type(MPI_Comm) :: comm
    integer :: rank = 0
    integer :: size = 1
  end type sweep_comm_t

  !> One send buffer; it must stay put until its request completes.
  type :: send_buffer_t
    real(dp), allocatable :: values(:)
  end type send_buffer_t

  ! The pool of sends in flight: allocated once, never moved while MPI holds it.
  type(send_buffer_t), allocatable, target, asynchronous, save :: buffers(:)
  type(MPI_Request), allocatable, save :: requests(:)

  interface
    function usleep(us) bind(c, name='usleep') result(rc)
      import :: c_int
      integer(c_int), value :: us
      integer(c_int) :: rc
    end function usleep
  end interface

contains

  subroutine comm_start(net)
    type(sweep_comm_t), intent(out) :: net
    call MPI_Init()
    call MPI_Comm_dup(MPI_COMM_WORLD, net%comm)
    call MPI_Comm_rank(net%comm, net%rank)
    call MPI_Comm_size(net%comm, net%size)
    ! Rank 0 has at most two tasks and a stop in flight per worker.
    allocate (buffers(3*net%size + 8), requests(3*net%size + 8))
    requests = MPI_REQUEST_NULL
  end subroutine comm_start

  !> Wait for the sends in flight, then leave MPI.
  subroutine comm_end(net)
    type(sweep_comm_t), intent(inout) :: net
    call MPI_Waitall(size(requests), requests, MPI_STATUSES_IGNORE)
    call MPI_Comm_free(net%comm)
    call MPI_Finalize()
  end subroutine comm_end

  !> Stop every rank after an error (the message was printed by the caller).
  subroutine comm_abort(net, code)
    type(sweep_comm_t), intent(in) :: net
    integer, intent(in) :: code
    flush (output_unit)
    call MPI_Abort(net%comm, code)
  end subroutine comm_abort

  !> Whether rank 0's `ok` holds, on every rank.
  logical function comm_agree(net, ok)
    type(sweep_comm_t), intent(in) :: net
    logical, intent(in) :: ok
    integer :: flag
    flag = merge(1, 0, ok)
    call MPI_Bcast(flag, 1, MPI_INTEGER, 0, net%comm)
    comm_agree = flag == 1
  end function comm_agree

  !> Send `msg` to `dest` without waiting for it to be received.
  subroutine comm_send(net, dest, tag, msg)
    type(sweep_comm_t), intent(in) :: net
    integer, intent(in) :: dest, tag
    real(dp), intent(in) :: msg(:)
    integer :: k, slot
    logical :: done
    slot = 0
    do k = 1, size(requests)
      if (requests(k) /= MPI_REQUEST_NULL) call MPI_Test(requests(k), done, MPI_STATUS_IGNORE)
      if (requests(k) == MPI_REQUEST_NULL) then
        slot = k
        exit
      end if
    end do
    if (slot == 0) call MPI_Waitany(size(requests), requests, slot, MPI_STATUS_IGNORE)
    buffers(slot)%values = msg
    call MPI_Isend(buffers(slot)%values, size(msg), MPI_DOUBLE_PRECISION, dest, tag, net%comm, requests(slot))
  end subroutine comm_send

  !> Whether a message from `source` (any rank if negative) is waiting: its sender, tag
  !> and length.
  subroutine comm_poll(net, source, waiting, sender, tag, length)
    type(sweep_comm_t), intent(in) :: net
    integer, intent(in) :: source
    logical, intent(out) :: waiting
    integer, intent(out) :: sender, tag, length
    type(MPI_Status) :: st
    if (source < 0) then
      call MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, net%comm, waiting, st)
    else
      call MPI_Iprobe(source, MPI_ANY_TAG, net%comm, waiting, st)
    end if
    sender = -1
    tag = -1
    length = 0
    if (waiting) then
      sender = st%MPI_SOURCE
      tag = st%MPI_TAG
      call MPI_Get_count(st, MPI_DOUBLE_PRECISION, length)
    end if
  end subroutine comm_poll

  !> Receive the message `comm_poll` announced.
  subroutine comm_recv(net, sender, tag, length, msg)
    type(sweep_comm_t), intent(in) :: net
    integer, intent(in) :: sender, tag, length
    real(dp), allocatable, intent(out) :: msg(:)
    allocate (msg(length))
    call MPI_Recv(msg, length, MPI_DOUBLE_PRECISION, sender, tag, net%comm, MPI_STATUS_IGNORE)
  end subroutine comm_recv

  real(dp) function wall_s()
    wall_s = MPI_Wtime()
  end function wall_s

  !> Let the core go for a moment (an MPI wait would spin on it).
  subroutine nap()
    integer(c_int) :: rc
    rc = usleep(int(nap_us, c_int))
  end subroutine nap

end module voussoir_sweep_comm

!> The master (rank 0: schedules, computes, writes) and the workers (compute).
!>
!> Scheduling is dynamic and per run: a threshold search is a state machine that asks
!> for one run at a time, so the unit of work is one simulation whatever the mode, and
!> every search with no run in flight is ready. Rank 0 computes too: between its own
!> runs it receives the results that have arrived (MPI_Iprobe) and hands out new tasks;
!> it takes its own runs from the cheap end of the queue, the workers get the costly end.
!> Two things keep the workers busy while rank 0 is inside a run and cannot answer:
!> a worker holds up to two tasks (one running, one queued), and a task of a threshold
!> search carries the outcomes of its earlier runs, so that a worker with nothing queued
!> goes on with the same search by itself (the search is deterministic: any rank that
!> has its history proposes the same next amplitude) and tells rank 0 so with the result.
module voussoir_sweep_roles
  use, intrinsic :: iso_fortran_env, only: output_unit
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_version, only: code_version
  use voussoir_config, only: config_t
  use voussoir_text, only: fmt_real, itoa
  use voussoir_assembly, only: assembly_t
  use voussoir_model, only: model_t
  use voussoir_simulation, only: run_result_t
  use voussoir_setup, only: run_config
  use voussoir_threshold, only: threshold_search_t, threshold_result_t, run_outcome_t, threshold_init, &
                                threshold_next, threshold_record, threshold_result, threshold_done, &
                                outcome_of_run
  use voussoir_sweep_output, only: sweep_table_t, sweep_header_t, results_table, runs_table, table_init, &
                                   table_append, table_value, table_sort, table_row, table_set, write_sweep_file, &
                                   read_sweep_file, write_sweep_csv, csv_path_of
  use voussoir_sweep_plan, only: sweep_plan_t, job_param_set, job_frequency_hz, job_amplitude_m, &
                                 job_run_config, job_cost, set_description
  use voussoir_sweep_comm, only: sweep_comm_t, comm_abort, comm_send, comm_poll, comm_recv, wall_s, nap, &
                                 tag_task, tag_result, tag_stop
  implicit none
  private

  public :: master_t, master_prepare, master_run, worker_run

  integer, parameter :: job_ready = 0, job_running = 1, job_done = 2
  integer, parameter :: prefetch = 2                        !! tasks a worker may hold
  !> Above this many ranks rank 0 only serves: one core more matters little then, and
  !> its answers must not wait for a run of its own.
  integer, parameter :: max_ranks_computing_master = 16
  !> Message layouts (reals): a task is [job, run, amplitude_m, n, then n x (amplitude_m,
  !> collapsed, peak_crown_disp_m) of the search's earlier runs]; a result is
  !> [job, run, continuing, then the outcome].
  integer, parameter :: task_head = 4, history_width = 3, result_len = 11
  real(dp), parameter :: first_guess_runs = 12.0_dp         !! runs of a search, before any ended
  !> Longest sweep summary printed at the end [jobs].
  integer, parameter :: max_listed_jobs = 60

  !> A task waiting on a worker.
  type :: queued_task_t
    real(dp), allocatable :: msg(:)
  end type queued_task_t

  !> The state of the sweep on rank 0.
  type :: master_t
    integer, allocatable :: state(:)                       !! (0:n_jobs-1) ready, running, done
    type(threshold_search_t), allocatable :: search(:)     !! (0:n_jobs-1) threshold mode
    logical, allocatable :: started(:)                     !! search initialised
    integer, allocatable :: order(:)                       !! jobs, costliest run first
    real(dp), allocatable :: cost(:)                       !! (0:n_jobs-1) relative cost of a run
    integer, allocatable :: outstanding(:)                 !! (1:n_ranks-1) tasks held by a worker
    integer :: front = 1, back = 0                         !! grid: no ready job outside order(front:back)
    type(sweep_table_t) :: results, runs
    type(sweep_header_t) :: header
    character(len=:), allocatable :: path, csv_path
    character(len=:), allocatable :: finished_by          !! code version of a finished file
    integer :: n_ready = 0                                 !! jobs in state ready
    integer :: n_done = 0, n_runs = 0, n_runs_resumed = 0
    real(dp) :: t0_s = 0.0_dp, last_report_s = 0.0_dp, cost_done = 0.0_dp
    real(dp) :: busy_s = 0.0_dp                            !! wall time of the runs of this session
  end type master_t

contains

  !> Set up rank 0: the file to write, and what an earlier run of the same sweep left in it.
  subroutine master_prepare(plan, base, n_ranks, m, status)
    type(sweep_plan_t), intent(in) :: plan
    type(config_t), intent(in) :: base
    integer, intent(in) :: n_ranks
    type(master_t), intent(out) :: m
    type(status_t), intent(inout) :: status
    type(sweep_table_t) :: by_cost
    logical :: exists
    integer :: job
    character(len=:), allocatable :: written_by

    m%path = trim(base%output%file)
    if (m%path == 'voussoir_run.h5') m%path = 'voussoir_sweep.h5'   ! the default is voussoir-run's
    m%csv_path = csv_path_of(m%path)
    allocate (m%state(0:plan%n_jobs - 1), m%started(0:plan%n_jobs - 1), m%cost(0:plan%n_jobs - 1), &
              m%outstanding(1:max(1, n_ranks - 1)))
    m%state = job_ready
    m%n_ready = plan%n_jobs
    m%started = .false.
    m%outstanding = 0
    if (plan%mode == 'threshold') allocate (m%search(0:plan%n_jobs - 1))
    ! Costliest first, ties by job index (the sort is stable).
    call table_init(by_cost, ['minus_cost', 'job       '], [.false., .true.])
    do job = 0, plan%n_jobs - 1
      m%cost(job) = job_cost(plan, job)
      call table_append(by_cost, [-m%cost(job), real(job, dp)])
    end do
    call table_sort(by_cost, ['minus_cost'])
    allocate (m%order(plan%n_jobs))
    do job = 1, plan%n_jobs
      m%order(job) = nint(table_value(by_cost, 'job', job))
    end do
    m%front = 1
    m%back = plan%n_jobs

    m%header%cfg = base
    m%header%cfg%output%file = m%path
    m%header%mode = plan%mode
    m%header%signature = plan%signature
    m%header%sweep_nml = plan%sweep_nml
    m%header%n_jobs = plan%n_jobs
    m%header%parameter_names = join(plan%param_names)
    m%header%parameter_values = plan%param_values
    m%header%frequencies_hz = plan%frequencies_hz
    m%header%amplitudes_m = plan%amplitudes_m

    m%results = results_table(plan%mode)
    if (plan%mode == 'threshold') m%runs = runs_table()
    inquire (file=m%path, exist=exists)
    if (.not. exists) return
    call read_sweep_file(m%path, plan%signature, m%results, m%runs, written_by, status)
    if (.not. status%ok) return
    if (written_by /= code_version) then
      ! A finished sweep stays as it is; an unfinished one cannot be continued by other code.
      if (m%results%n_rows == plan%n_jobs) then
        m%finished_by = written_by
        return
      end if
      call fail(status, m%path//": was written by '"//written_by//"', this is '"//code_version// &
                "'; results of two code versions are never mixed: finish the sweep with the first "// &
                'build, or move the file away')
      return
    end if
    call restore(plan, m, status)
  end subroutine master_prepare

  !> Mark the jobs the file holds as done and replay the runs of unfinished searches.
  subroutine restore(plan, m, status)
    type(sweep_plan_t), intent(in) :: plan
    type(master_t), intent(inout) :: m
    type(status_t), intent(inout) :: status
    integer :: r, job, seq
    type(run_outcome_t) :: o
    real(dp) :: amp_m
    logical :: done

    do r = 1, m%results%n_rows
      job = nint(table_value(m%results, 'job', r))
      if (job < 0 .or. job >= plan%n_jobs) then
        call fail(status, m%path//': /results holds job '//itoa(job)//', outside this sweep')
        return
      else if (m%state(job) == job_done) then
        call fail(status, m%path//': /results holds job '//itoa(job)//' twice')
        return
      end if
      call set_state(m, job, job_done)
      m%n_done = m%n_done + 1
    end do
    if (plan%mode == 'threshold') then
      ! Replay the runs of each unfinished search in its own order: the search asks for
      ! the same amplitudes again, and continues where it stopped.
      call table_sort(m%runs, ['job', 'run'])
      do r = 1, m%runs%n_rows
        job = nint(table_value(m%runs, 'job', r))
        seq = nint(table_value(m%runs, 'run', r))
        if (job < 0 .or. job >= plan%n_jobs) then
          call fail(status, m%path//': /runs holds job '//itoa(job)//', outside this sweep')
          return
        end if
        if (m%state(job) == job_done) cycle
        call start_search(plan, m, job, status)
        if (.not. status%ok) return
        call threshold_next(m%search(job), amp_m, done)
        o = outcome_from_row(m%runs, r)
        if (done .or. seq /= m%search(job)%n_runs .or. o%amplitude_m /= amp_m) then
          call fail(status, m%path//': run '//itoa(seq)//' of job '//itoa(job)// &
                    ' does not follow the search of this input; the file cannot be continued')
          return
        end if
        call threshold_record(m%search(job), o, status)
        if (.not. status%ok) return
        if (threshold_done(m%search(job))) call finish_search(plan, m, job)
      end do
      m%n_runs_resumed = m%runs%n_rows
    else
      m%n_runs_resumed = m%results%n_rows
    end if
  end subroutine restore

  !> The sweep on rank 0: serve the workers, compute, write, report.
  subroutine master_run(plan, net, m)
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_comm_t), intent(in) :: net
    type(master_t), intent(inout) :: m
    type(status_t) :: status
    integer :: job, w
    logical :: found, got
    character(len=:), allocatable :: amps

    m%t0_s = wall_s()
    m%last_report_s = m%t0_s
    if (plan%pair_frequencies) then
      amps = itoa(plan%n_sets)//' parameter sets, each at its frequency'
    else
      amps = itoa(plan%n_sets)//' parameter sets x '//itoa(plan%n_freq)//' frequencies'
    end if
    if (plan%mode == 'grid') amps = amps//' x '//itoa(plan%n_amp)//' amplitudes'
    write (output_unit, '(a)') 'voussoir-sweep: '//trim(plan%mode)//' sweep of '//itoa(plan%n_jobs)//' jobs ('// &
      amps//') on '//itoa(net%size)//' ranks -> '//m%path
    if (m%n_done > 0 .or. m%n_runs_resumed > 0) write (output_unit, '(a)') 'voussoir-sweep: resuming '// &
      m%path//': '//itoa(m%n_done)//' of '//itoa(plan%n_jobs)//' jobs done, '//itoa(m%n_runs_resumed)// &
      ' runs kept'
    flush (output_unit)
    if (allocated(m%finished_by)) then
      write (output_unit, '(a)') 'voussoir-sweep: '//m%path//' is complete, written by '//m%finished_by// &
        '; nothing to do (move it away to recompute it with this build)'
      do w = 1, net%size - 1
        call comm_send(net, w, tag_stop, [0.0_dp])
      end do
      return
    end if
    if (m%n_done < plan%n_jobs) call write_state(m, .false.)

    call hand_out(plan, net, m)
    do while (m%n_done < plan%n_jobs)
      call serve(plan, net, m, got)
      if (got) call write_state(m, .false.)
      if (m%n_done == plan%n_jobs) exit
      found = .false.
      if (net%size <= max_ranks_computing_master) call pick(plan, m, .false., job, found)
      if (found) then
        call run_own(job)
        call write_state(m, .false.)
      else
        call nap()
      end if
      call report(plan, m, net%size, .false.)
    end do
    do w = 1, net%size - 1
      call comm_send(net, w, tag_stop, [0.0_dp])
    end do

    call table_sort(m%results, ['job'])
    if (plan%mode == 'threshold') call table_sort(m%runs, ['job', 'run'])
    call write_state(m, .true.)
    call write_sweep_csv(m%csv_path, m%header, m%results, status)
    if (.not. status%ok) call die(status%message)
    call report(plan, m, net%size, .true.)
    call summary(plan, m)

  contains

    subroutine run_own(job)
      integer, intent(in) :: job
      integer :: seq
      real(dp) :: amp_m
      type(run_outcome_t) :: o
      call next_run(plan, m, job, seq, amp_m)
      call set_state(m, job, job_running)
      call simulate_job(plan, job, amp_m, o, status)
      if (.not. status%ok) call die('rank 0, '//trim(status%message))
      call take_result(plan, m, job, seq, o, .false., status)
      if (.not. status%ok) call die(status%message)
    end subroutine run_own

    subroutine write_state(mm, complete)
      type(master_t), intent(in) :: mm
      logical, intent(in) :: complete
      call write_sweep_file(mm%path, mm%header, mm%results, mm%runs, complete, status)
      if (.not. status%ok) call die(status%message)
    end subroutine write_state

    subroutine die(message)
      character(len=*), intent(in) :: message
      write (output_unit, '(a)') 'voussoir-sweep: error: '//trim(message)
      call comm_abort(net, 1)
    end subroutine die

  end subroutine master_run

  !> Receive every result that has arrived, then refill the workers.
  subroutine serve(plan, net, m, got)
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_comm_t), intent(in) :: net
    type(master_t), intent(inout) :: m
    logical, intent(out) :: got
    real(dp), allocatable :: msg(:)
    logical :: waiting, continuing
    integer :: sender, tag, length
    type(status_t) :: status
    got = .false.
    do
      call comm_poll(net, -1, waiting, sender, tag, length)
      if (.not. waiting) exit
      call comm_recv(net, sender, tag, length, msg)
      if (tag /= tag_result .or. length /= result_len) cycle
      ! A worker that goes on with the same search keeps its task.
      continuing = msg(3) == 1.0_dp
      if (.not. continuing) m%outstanding(sender) = m%outstanding(sender) - 1
      call take_result(plan, m, nint(msg(1)), nint(msg(2)), outcome_of_msg(msg), continuing, status)
      if (.not. status%ok) then
        write (output_unit, '(a)') 'voussoir-sweep: error: '//trim(status%message)
        call comm_abort(net, 1)
      end if
      got = .true.
    end do
    call hand_out(plan, net, m)
  end subroutine serve

  !> Give each worker up to `prefetch` tasks, costliest first; a second task only while
  !> one more stays ready for rank 0.
  subroutine hand_out(plan, net, m)
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_comm_t), intent(in) :: net
    type(master_t), intent(inout) :: m
    integer :: slot, w, job, seq, k
    real(dp) :: amp_m
    real(dp), allocatable :: msg(:)
    logical :: found
    do slot = 1, prefetch
      do w = 1, net%size - 1
        if (m%outstanding(w) >= slot) cycle
        if (slot > 1 .and. m%n_ready <= 1) return
        call pick(plan, m, .true., job, found)
        if (.not. found) return
        call next_run(plan, m, job, seq, amp_m)
        call set_state(m, job, job_running)
        m%outstanding(w) = m%outstanding(w) + 1
        allocate (msg(task_head + history_width*seq))
        msg(1:task_head) = [real(job, dp), real(seq, dp), amp_m, real(seq, dp)]
        do k = 1, seq
          associate (o => m%search(job)%runs(k))
            msg(task_head + history_width*(k - 1) + 1:task_head + history_width*k) = &
              [o%amplitude_m, merge(1.0_dp, 0.0_dp, o%collapsed), o%peak_crown_disp_m]
          end associate
        end do
        call comm_send(net, w, tag_task, msg)
        deallocate (msg)
      end do
    end do
  end subroutine hand_out

  !> A ready job: the costliest (for a worker) or the cheapest (for rank 0).
  subroutine pick(plan, m, costliest, job, found)
    type(sweep_plan_t), intent(in) :: plan
    type(master_t), intent(inout) :: m
    logical, intent(in) :: costliest
    integer, intent(out) :: job
    logical, intent(out) :: found
    integer :: k
    found = .false.
    job = -1
    if (plan%mode == 'grid') then
      ! Grid jobs never become ready again: the ends of the order only move inwards.
      do while (m%front <= m%back)
        if (costliest) then
          k = m%front
        else
          k = m%back
        end if
        if (m%state(m%order(k)) == job_ready) then
          job = m%order(k)
          found = .true.
          return
        end if
        if (costliest) then
          m%front = m%front + 1
        else
          m%back = m%back - 1
        end if
      end do
    else
      do k = 1, plan%n_jobs
        job = m%order(merge(k, plan%n_jobs + 1 - k, costliest))
        if (m%state(job) == job_ready) then
          found = .true.
          return
        end if
      end do
      job = -1
    end if
  end subroutine pick

  !> Move job `job` to state `new`, keeping count of the ready ones.
  subroutine set_state(m, job, new)
    type(master_t), intent(inout) :: m
    integer, intent(in) :: job, new
    if (m%state(job) == job_ready) m%n_ready = m%n_ready - 1
    if (new == job_ready) m%n_ready = m%n_ready + 1
    m%state(job) = new
  end subroutine set_state

  !> Sequence number and amplitude of the next run of a ready job.
  subroutine next_run(plan, m, job, seq, amp_m)
    type(sweep_plan_t), intent(in) :: plan
    type(master_t), intent(inout) :: m
    integer, intent(in) :: job
    integer, intent(out) :: seq
    real(dp), intent(out) :: amp_m
    logical :: done
    type(status_t) :: status
    if (plan%mode == 'grid') then
      seq = 0
      amp_m = job_amplitude_m(plan, job)
    else
      call start_search(plan, m, job, status)   ! checked when the plan was read
      seq = m%search(job)%n_runs
      call threshold_next(m%search(job), amp_m, done)
    end if
  end subroutine next_run

  subroutine start_search(plan, m, job, status)
    type(sweep_plan_t), intent(in) :: plan
    type(master_t), intent(inout) :: m
    integer, intent(in) :: job
    type(status_t), intent(inout) :: status
    if (m%started(job)) return
    call threshold_init(m%search(job), plan%set_cfg(job_param_set(plan, job)), job_frequency_hz(plan, job), &
                        plan%search, status)
    m%started(job) = .true.
  end subroutine start_search

  !> Record the outcome of run `seq` of job `job`; `continuing`: the rank that made it
  !> goes on with the same search.
  subroutine take_result(plan, m, job, seq, o, continuing, status)
    type(sweep_plan_t), intent(in) :: plan
    type(master_t), intent(inout) :: m
    integer, intent(in) :: job, seq
    type(run_outcome_t), intent(in) :: o
    logical, intent(in) :: continuing
    type(status_t), intent(inout) :: status
    real(dp), allocatable :: row(:)
    m%n_runs = m%n_runs + 1
    m%cost_done = m%cost_done + m%cost(job)
    m%busy_s = m%busy_s + o%wall_time_s
    if (plan%mode == 'grid') then
      call table_row(m%results, row)
      call table_set(m%results, row, 'job', real(job, dp))
      call table_set(m%results, row, 'param_set', real(job_param_set(plan, job), dp))
      call table_set(m%results, row, 'frequency_hz', job_frequency_hz(plan, job))
      call table_set(m%results, row, 'amplitude_m', o%amplitude_m)
      call table_set(m%results, row, 'collapsed', merge(1.0_dp, 0.0_dp, o%collapsed))
      call table_set(m%results, row, 'collapse_time_s', o%collapse_time_s)
      call table_set(m%results, row, 'peak_crown_disp_m', o%peak_crown_disp_m)
      call table_set(m%results, row, 'mean_iterations', o%mean_iterations)
      call table_set(m%results, row, 'nonconverged_steps', real(o%nonconverged_steps, dp))
      call table_set(m%results, row, 'wall_time_s', o%wall_time_s)
      call table_append(m%results, row)
      call set_state(m, job, job_done)
      m%n_done = m%n_done + 1
      return
    end if
    if (seq /= m%search(job)%n_runs) then
      call fail(status, 'internal: run '//itoa(seq)//' of job '//itoa(job)//' arrived out of order')
      return
    end if
    call table_row(m%runs, row)
    call table_set(m%runs, row, 'job', real(job, dp))
    call table_set(m%runs, row, 'run', real(seq, dp))
    call table_set(m%runs, row, 'amplitude_m', o%amplitude_m)
    call table_set(m%runs, row, 'collapsed', merge(1.0_dp, 0.0_dp, o%collapsed))
    call table_set(m%runs, row, 'collapse_time_s', o%collapse_time_s)
    call table_set(m%runs, row, 'peak_crown_disp_m', o%peak_crown_disp_m)
    call table_set(m%runs, row, 'mean_iterations', o%mean_iterations)
    call table_set(m%runs, row, 'n_steps', real(o%n_steps, dp))
    call table_set(m%runs, row, 'nonconverged_steps', real(o%nonconverged_steps, dp))
    call table_set(m%runs, row, 'wall_time_s', o%wall_time_s)
    call table_append(m%runs, row)
    call threshold_record(m%search(job), o, status)
    if (.not. status%ok) return
    if (threshold_done(m%search(job))) then
      call finish_search(plan, m, job)
    else if (continuing) then
      call set_state(m, job, job_running)
    else
      call set_state(m, job, job_ready)
    end if
  end subroutine take_result

  !> The /results row of a finished search.
  subroutine finish_search(plan, m, job)
    type(sweep_plan_t), intent(in) :: plan
    type(master_t), intent(inout) :: m
    integer, intent(in) :: job
    type(threshold_result_t) :: r
    real(dp), allocatable :: row(:)
    r = threshold_result(m%search(job))
    call table_row(m%results, row)
    call table_set(m%results, row, 'job', real(job, dp))
    call table_set(m%results, row, 'param_set', real(job_param_set(plan, job), dp))
    call table_set(m%results, row, 'frequency_hz', job_frequency_hz(plan, job))
    call table_set(m%results, row, 'threshold_m', r%threshold_m)
    call table_set(m%results, row, 'peak_accel_m_s2', r%peak_accel_m_s2)
    call table_set(m%results, row, 'non_monotonic', merge(1.0_dp, 0.0_dp, r%non_monotonic))
    call table_set(m%results, row, 'n_runs', real(r%n_runs, dp))
    call table_set(m%results, row, 'mean_iterations', r%mean_iterations)
    call table_set(m%results, row, 'stand_below_m', r%stand_below_m)
    call table_set(m%results, row, 'static_onset_m', r%onset_amp_m)
    call table_set(m%results, row, 'wall_time_s', r%wall_time_s)
    call table_append(m%results, row)
    call set_state(m, job, job_done)
    m%n_done = m%n_done + 1
  end subroutine finish_search

  !> A progress line every `progress_every_s` (and the last one): jobs and runs done,
  !> elapsed time, and the time left estimated from the cost of the runs still to come.
  subroutine report(plan, m, n_ranks, final)
    type(sweep_plan_t), intent(in) :: plan
    type(master_t), intent(inout) :: m
    integer, intent(in) :: n_ranks
    logical, intent(in) :: final
    real(dp) :: now_s, elapsed_s, left, runs_per_search, eta_s, runs_left
    integer :: job, r, done_runs
    character(len=:), allocatable :: runs
    character(len=32) :: eta
    now_s = wall_s()
    if (.not. final .and. now_s - m%last_report_s < plan%progress_every_s) return
    m%last_report_s = now_s
    elapsed_s = now_s - m%t0_s
    if (final) then
      ! Busy: the simulations' share of the ranks' time (the rest is waiting, messages, I/O).
      write (output_unit, '(a)') 'voussoir-sweep: done: '//itoa(plan%n_jobs)//' jobs, '// &
        itoa(m%n_runs)//' runs in '//fixed(elapsed_s, 2)//' s on '//itoa(n_ranks)//' ranks (busy '// &
        fixed(100.0_dp*m%busy_s/max(n_ranks*elapsed_s, tiny(1.0_dp)), 1)//' %; '//itoa(m%n_runs_resumed)// &
        ' runs kept from the file); '//m%path//', '//m%csv_path
      flush (output_unit)
      return
    end if
    ! Work left, in run costs; a search is expected to take as many runs as the finished ones.
    runs_per_search = first_guess_runs
    if (plan%mode == 'threshold' .and. m%results%n_rows > 0) then
      runs_per_search = 0.0_dp
      do r = 1, m%results%n_rows
        runs_per_search = runs_per_search + table_value(m%results, 'n_runs', r)/m%results%n_rows
      end do
    end if
    left = 0.0_dp
    runs_left = 0.0_dp
    do job = 0, plan%n_jobs - 1
      if (m%state(job) == job_done) cycle
      if (plan%mode == 'grid') then
        runs_left = runs_left + 1.0_dp
        left = left + m%cost(job)
      else
        runs_left = runs_left + max(1.0_dp, runs_per_search - m%search(job)%n_runs)
        left = left + m%cost(job)*max(1.0_dp, runs_per_search - m%search(job)%n_runs)
      end if
    end do
    eta = '?'
    if (m%cost_done > 0.0_dp) then
      eta_s = elapsed_s*left/m%cost_done
      if (eta_s < 120.0_dp) then
        eta = itoa(nint(eta_s))//' s'
      else if (eta_s < 7200.0_dp) then
        eta = itoa(nint(eta_s/60.0_dp))//' min'
      else
        eta = fixed(eta_s/3600.0_dp, 1)//' h'
      end if
    end if
    ! Runs done / total (a threshold search's total is an estimate until it ends).
    done_runs = m%n_runs + m%n_runs_resumed
    if (plan%mode == 'grid') then
      runs = itoa(done_runs)//'/'//itoa(plan%n_jobs)//' runs'
    else
      runs = itoa(m%n_done)//'/'//itoa(plan%n_jobs)//' searches, '//itoa(done_runs)//'/~'// &
             itoa(done_runs + nint(runs_left))//' runs'
    end if
    write (output_unit, '(a)') 'voussoir-sweep: '//runs//', elapsed '//fixed(elapsed_s, 1)//' s, ETA '//trim(eta)
    flush (output_unit)
  end subroutine report

  !> The thresholds of a short sweep, for the log.
  subroutine summary(plan, m)
    type(sweep_plan_t), intent(in) :: plan
    type(master_t), intent(in) :: m
    real(dp) :: thr
    integer :: r, job, n_runs
    character(len=160) :: line
    if (plan%mode /= 'threshold' .or. plan%n_jobs > max_listed_jobs) return
    do r = 1, m%results%n_rows
      job = nint(table_value(m%results, 'job', r))
      thr = table_value(m%results, 'threshold_m', r)
      n_runs = nint(table_value(m%results, 'n_runs', r))
      if (thr == thr) then
        write (line, '(a,f7.3,a,f9.3,a,f8.3,a,i3,a)') '  f = ', job_frequency_hz(plan, job), &
          ' Hz: threshold ', 1.0e3_dp*thr, ' mm (', table_value(m%results, 'peak_accel_m_s2', r), &
          ' m/s2), ', n_runs, ' runs'
      else
        write (line, '(a,f7.3,a,i3,a)') '  f = ', job_frequency_hz(plan, job), ' Hz: stands up to amp_max_m, ', &
          n_runs, ' runs'
      end if
      if (nint(table_value(m%results, 'non_monotonic', r)) == 1) line = trim(line)//', non-monotonic'
      write (output_unit, '(a)') trim(line)//'  ['//set_description(plan, job_param_set(plan, job))//']'
    end do
    flush (output_unit)
  end subroutine summary

  !> A worker: run the tasks rank 0 sends and return each outcome, until told to stop.
  !> With nothing queued after a run of a threshold search, go on with that search.
  subroutine worker_run(plan, net)
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_comm_t), intent(in) :: net
    type(queued_task_t) :: queue(prefetch + 1)
    type(threshold_search_t), allocatable :: replica(:)   ! searches as far as this rank knows them
    logical, allocatable :: known(:)
    real(dp), allocatable :: msg(:)
    integer :: n_queued, sender, tag, length, job, seq
    real(dp) :: amp_m
    logical :: waiting, stopping, busy, continuing, done
    type(run_outcome_t) :: o
    type(status_t) :: status

    if (plan%mode == 'threshold') allocate (replica(0:plan%n_jobs - 1))
    allocate (known(0:plan%n_jobs - 1))
    known = .false.
    n_queued = 0
    stopping = .false.
    busy = .false.
    do
      call receive_all()
      if (.not. busy) then
        if (n_queued == 0) then
          if (stopping) exit
          call nap()
          cycle
        end if
        msg = queue(1)%msg
        queue(1:n_queued - 1) = queue(2:n_queued)
        n_queued = n_queued - 1
        job = nint(msg(1))
        seq = nint(msg(2))
        amp_m = msg(3)
        if (plan%mode == 'threshold') call sync_replica(msg)
        busy = .true.
      end if
      call simulate_job(plan, job, amp_m, o, status)
      if (.not. status%ok) call die('rank '//itoa(net%rank)//', '//trim(status%message))
      continuing = .false.
      if (plan%mode == 'threshold') then
        call threshold_record(replica(job), o, status)
        if (.not. status%ok) call die(status%message)
        call receive_all()
        continuing = n_queued == 0 .and. .not. threshold_done(replica(job))
      end if
      call comm_send(net, 0, tag_result, msg_of_outcome(job, seq, continuing, o))
      busy = continuing
      if (continuing) then
        seq = seq + 1
        call threshold_next(replica(job), amp_m, done)
      end if
    end do

  contains

    subroutine receive_all()
      do
        call comm_poll(net, 0, waiting, sender, tag, length)
        if (.not. waiting) exit
        call comm_recv(net, 0, tag, length, msg)
        if (tag == tag_stop) then
          stopping = .true.
        else if (n_queued < size(queue)) then
          n_queued = n_queued + 1
          queue(n_queued)%msg = msg
        else
          call die('internal: rank '//itoa(net%rank)//' got more tasks than it can hold')
        end if
      end do
    end subroutine receive_all

    !> Bring the replica of search `job` to the history the task carries.
    subroutine sync_replica(task)
      real(dp), intent(in) :: task(:)
      integer :: k, n
      real(dp) :: next_m
      type(run_outcome_t) :: past
      n = nint(task(4))
      if (known(job)) then
        if (replica(job)%n_runs == n) return   ! this rank made the runs since it last synced
      end if
      call threshold_init(replica(job), plan%set_cfg(job_param_set(plan, job)), job_frequency_hz(plan, job), &
                          plan%search, status)
      do k = 1, n
        past%amplitude_m = task(task_head + history_width*(k - 1) + 1)
        past%collapsed = task(task_head + history_width*(k - 1) + 2) == 1.0_dp
        past%peak_crown_disp_m = task(task_head + history_width*(k - 1) + 3)
        if (status%ok) call threshold_record(replica(job), past, status)
      end do
      call threshold_next(replica(job), next_m, done)
      if (.not. status%ok .or. done .or. next_m /= amp_m) &
        call die('internal: rank '//itoa(net%rank)//' cannot follow the search of job '//itoa(job))
      known(job) = .true.
    end subroutine sync_replica

    subroutine die(message)
      character(len=*), intent(in) :: message
      write (output_unit, '(a)') 'voussoir-sweep: error: '//trim(message)
      call comm_abort(net, 1)
    end subroutine die

  end subroutine worker_run

  !> One simulation of job `job` at `amp_m`.
  subroutine simulate_job(plan, job, amp_m, o, status)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    real(dp), intent(in) :: amp_m
    type(run_outcome_t), intent(out) :: o
    type(status_t), intent(inout) :: status
    type(assembly_t) :: assembly
    type(model_t) :: model
    type(run_result_t) :: res
    call run_config(job_run_config(plan, job, amp_m), assembly, model, res, status)
    if (.not. status%ok) then
      status%message = 'job '//itoa(job)//' (parameter set '//itoa(job_param_set(plan, job))//', '// &
                       fmt_real(job_frequency_hz(plan, job))//' Hz, amplitude '//fmt_real(amp_m)//' m): '// &
                       trim(status%message)
      return
    end if
    o = outcome_of_run(amp_m, res)
  end subroutine simulate_job

  pure function msg_of_outcome(job, seq, continuing, o) result(msg)
    integer, intent(in) :: job, seq
    logical, intent(in) :: continuing
    type(run_outcome_t), intent(in) :: o
    real(dp) :: msg(result_len)
    msg = [real(job, dp), real(seq, dp), merge(1.0_dp, 0.0_dp, continuing), o%amplitude_m, &
           merge(1.0_dp, 0.0_dp, o%collapsed), o%collapse_time_s, o%peak_crown_disp_m, o%mean_iterations, &
           real(o%n_steps, dp), real(o%nonconverged_steps, dp), o%wall_time_s]
  end function msg_of_outcome

  pure function outcome_of_msg(msg) result(o)
    real(dp), intent(in) :: msg(result_len)
    type(run_outcome_t) :: o
    o%amplitude_m = msg(4)
    o%collapsed = msg(5) == 1.0_dp
    o%collapse_time_s = msg(6)
    o%peak_crown_disp_m = msg(7)
    o%mean_iterations = msg(8)
    o%n_steps = nint(msg(9))
    o%nonconverged_steps = nint(msg(10))
    o%wall_time_s = msg(11)
  end function outcome_of_msg

  !> The outcome stored in row `r` of a /runs table.
  function outcome_from_row(t, r) result(o)
    type(sweep_table_t), intent(in) :: t
    integer, intent(in) :: r
    type(run_outcome_t) :: o
    o%amplitude_m = value('amplitude_m')
    o%collapsed = nint(value('collapsed')) == 1
    o%collapse_time_s = value('collapse_time_s')
    o%peak_crown_disp_m = value('peak_crown_disp_m')
    o%mean_iterations = value('mean_iterations')
    o%n_steps = nint(value('n_steps'))
    o%nonconverged_steps = nint(value('nonconverged_steps'))
    o%wall_time_s = value('wall_time_s')
  contains
    real(dp) function value(name)
      character(len=*), intent(in) :: name
      value = table_value(t, name, r)
    end function value
  end function outcome_from_row

  !> `x` with `digits` decimals, and a 0 before the point.
  function fixed(x, digits) result(text)
    real(dp), intent(in) :: x
    integer, intent(in) :: digits
    character(len=:), allocatable :: text
    character(len=32) :: buf, fmt
    write (fmt, '(a,i0,a)') '(f0.', digits, ')'
    write (buf, fmt) x
    text = trim(adjustl(buf))
    if (text(1:1) == '.') text = '0'//text
    if (text(1:min(2, len(text))) == '-.') text = '-0'//text(2:)
  end function fixed

  function join(names) result(text)
    character(len=*), intent(in) :: names(:)
    character(len=:), allocatable :: text
    integer :: k
    text = ''
    do k = 1, size(names)
      if (k > 1) text = text//','
      text = text//trim(names(k))
    end do
  end function join


end module voussoir_sweep_roles

!> The program: read the input on every rank, let rank 0 check the result file, then
!> master and workers.
program voussoir_sweep
  use, intrinsic :: iso_fortran_env, only: output_unit
  use voussoir_status, only: status_t
  use voussoir_config, only: config_t, read_config
  use voussoir_sweep_plan, only: sweep_plan_t, read_sweep_plan
  use voussoir_sweep_comm, only: sweep_comm_t, comm_start, comm_end, comm_agree
  use voussoir_sweep_roles, only: master_t, master_prepare, master_run, worker_run
  implicit none
  type(sweep_comm_t) :: net
  type(config_t) :: cfg
  type(sweep_plan_t) :: plan
  type(master_t) :: master
  type(status_t) :: status
  character(len=1024) :: path

  call comm_start(net)
  if (command_argument_count() /= 1) then
    if (net%rank == 0) write (output_unit, '(a)') 'usage: mpirun -np N voussoir-sweep FILE.nml'
    call comm_end(net)
    stop 2, quiet=.true.
  end if
  call get_command_argument(1, path)
  call read_config(trim(path), [character(len=8) :: 'arch', 'motion', 'solver', 'output', 'sweep'], cfg, status)
  if (status%ok) call read_sweep_plan(trim(path), cfg, plan, status)
  if (status%ok .and. net%rank == 0) call master_prepare(plan, cfg, net%size, master, status)
  ! Every rank read the same input; only rank 0 knows whether the result file is usable.
  if (.not. comm_agree(net, status%ok)) then
    if (net%rank == 0) write (output_unit, '(a)') 'voussoir-sweep: error: '//trim(status%message)
    call comm_end(net)
    ! Every rank stops with code 1; quietly, since error stop would print a backtrace per rank.
    stop 1, quiet=.true.
  end if
  if (net%rank == 0) then
    call master_run(plan, net, master)
  else
    call worker_run(plan, net)
  end if
  call comm_end(net)
end program voussoir_sweep
