!> The sweep definition: the &sweep group, its parameter sets and its jobs.
!>
!> Modes: `threshold` (the smallest afd amplitude that collapses the arch, per
!> parameter set and frequency), `grid` (stand or collapse at given amplitudes) and `ida`
!> (the smallest scale of each record that collapses it, per parameter set and record;
!> the model samples and the records: src/sweep_ida.f90). What a job is: src/sweep_jobs.f90.
module voussoir_sweep_plan
  use, intrinsic :: iso_fortran_env, only: iostat_end
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: lower, itoa, int_list, join_words, fmt_exact_list
  use voussoir_config, only: config_t, config_entry_t, config_entries, config_to_nml, validate_config, &
                             fmt_real, arch_rule, arch_rule_text
  use voussoir_namelist_check, only: check_names, check_list_lengths
  use voussoir_threshold_search, only: threshold_settings_t
  use voussoir_sweep_ida, only: ida_records_t, read_ida_records, sample_sets, n_sampled, range_names
  implicit none
  private

  public :: sweep_plan_t, read_sweep_plan, set_description

  integer, parameter :: max_list = 256              !! entries of every &sweep list
  real(dp), parameter :: unset_real = -huge(1.0_dp) !! sentinel of an unset list entry
  integer, parameter :: unset_int = -huge(1)
  real(dp), parameter :: max_jobs = 1.0e7_dp
  integer, parameter :: max_records = 128          !! entries of &sweep record_files
  integer, parameter :: record_len = 256            !! characters of one record file name
  integer, parameter :: n_kinds = 5                 !! model parameters that can be swept
  character(len=*), parameter :: nl = achar(10)
  !> Swept parameters in the order of their columns, and their &sweep list names.
  character(len=24), parameter :: param_kinds(n_kinds) = [character(len=24) :: &
    'embrace_deg', 'n_voussoirs', 'thickness_m', 'friction', 'contact_inset_m']
  character(len=24), parameter :: list_names(n_kinds) = [character(len=24) :: &
    'embrace_list_deg', 'n_voussoirs_list', 'thickness_list_m', 'friction_list', 'contact_inset_list_m']

  !> Everything a rank needs to turn a job index into a run.
  type :: sweep_plan_t
    character(len=16) :: mode = 'threshold'       !! threshold, grid or ida
    character(len=16) :: combine = 'product'      !! product or paired
    logical :: pair_frequencies = .false.         !! frequency k goes with parameter set k only
    real(dp), allocatable :: frequencies_hz(:)
    real(dp), allocatable :: amplitudes_m(:)      !! grid mode
    type(threshold_settings_t) :: search          !! threshold and ida modes (ida: over the scale)
    type(ida_records_t) :: records                !! ida mode
    integer :: n_samples = 0                      !! ida: Latin hypercube model samples (0: the lists)
    integer :: sample_seed = 1                    !! ida: seed of the samples
    integer :: dt_check_rows = 0                  !! ida: rows whose two bracketing runs are redone at dt/2
    real(dp) :: progress_every_s = 10.0_dp        !! seconds between progress lines
    integer :: n_params = 0, n_sets = 1, n_freq = 0, n_amp = 1, n_jobs = 0
    integer :: n_freq_per_set = 0                 !! n_freq, or 1 with pair_frequencies; ida: the records
    character(len=24), allocatable :: param_names(:)
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
    character(len=record_len) :: record_files(max_records)
    real(dp) :: scale_tol, scale_max, friction_range(2), contact_inset_range_m(2), thickness_range_m(2), &
                size_imperfection_range(2)
    integer :: n_samples, sample_seed, dt_check_rows
    namelist /sweep/ mode, combine, pair_frequencies, frequencies_hz, amplitudes_m, amp_tol_m, amp_max_m, scan_step, &
      refine_factor, n_confirm, progress_every_s, embrace_list_deg, n_voussoirs_list, thickness_list_m, &
      friction_list, contact_inset_list_m, record_files, scale_tol, scale_max, n_samples, sample_seed, &
      friction_range, contact_inset_range_m, thickness_range_m, size_imperfection_range, dt_check_rows
    real(dp) :: ranges(2, n_sampled)
    integer :: n_records
    type(threshold_settings_t) :: defaults
    real(dp) :: lists(max_list, n_kinds), f_max_hz
    integer :: lengths(n_kinds), unit, ios, j, k, n_freq, n_amp
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
    record_files = ''
    scale_tol = 0.05_dp
    scale_max = 20.0_dp
    n_samples = 0
    sample_seed = 1
    dt_check_rows = 0
    friction_range = unset_real
    contact_inset_range_m = unset_real
    thickness_range_m = unset_real
    size_imperfection_range = unset_real

    call check_names(path, 'sweep', [character(len=24) :: 'mode', 'combine', 'pair_frequencies', &
      'frequencies_hz', 'amplitudes_m', 'amp_tol_m', 'amp_max_m', 'scan_step', 'refine_factor', 'n_confirm', &
      'progress_every_s', list_names, 'record_files', 'scale_tol', 'scale_max', 'n_samples', 'sample_seed', &
      range_names, 'dt_check_rows'], status)
    call check_list_lengths(path, 'sweep', [character(len=24) :: 'frequencies_hz', 'amplitudes_m', list_names, &
      'record_files', range_names], [max_list, max_list, spread(max_list, 1, n_kinds), max_records, &
      spread(2, 1, size(range_names))], status)
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
    case ('threshold', 'grid', 'ida')
    case default
      call fail(status, path//": &sweep mode = '"//trim(mode)//"' is not one of 'threshold', 'grid', 'ida'")
      return
    end select
    select case (plan%combine)
    case ('product', 'paired')
    case default
      call fail(status, path//": &sweep combine = '"//trim(combine)//"' is not one of 'product', 'paired'")
      return
    end select
    ranges = reshape([friction_range, contact_inset_range_m, thickness_range_m, size_imperfection_range], &
                     [2, n_sampled])
    if (plan%mode == 'ida') then
      call read_ida_part()
      if (.not. status%ok) return
    else
      if (any(ranges /= unset_real) .or. n_samples /= 0 .or. len_trim(record_files(1)) > 0 .or. &
          dt_check_rows /= 0) then
        call fail(status, path//": &sweep record_files, scale_tol, scale_max, n_samples, the sampling ranges "// &
                  "and dt_check_rows belong to mode = 'ida', not '"//trim(plan%mode)//"'")
        return
      end if
    end if
    if (plan%mode /= 'ida' .and. base%motion%waveform /= 'afd') then
      call fail(status, path//": &motion waveform = '"//trim(base%motion%waveform)// &
                "': a sweep sets the frequency and amplitude of the 'afd' waveform; use waveform = 'afd'")
      return
    end if

    ! Frequencies: at least one, each resolved by at least 20 steps per cycle.
    n_freq = list_length(frequencies_hz, 'frequencies_hz')
    if (.not. status%ok) return
    if (plan%mode == 'ida') then
      if (n_freq > 0) then
        call fail(status, path//": &sweep frequencies_hz is set but mode = 'ida' plays records: remove it")
        return
      end if
    else if (n_freq == 0) then
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
    if (plan%mode == 'ida') then
      if (n_amp > 0) then
        call fail(status, path//": &sweep amplitudes_m is set but mode = 'ida' searches the scale of each "// &
                  'record: remove it')
        return
      end if
      n_amp = 1
    else if (plan%mode == 'grid') then
      if (n_amp == 0) then
        call fail(status, path//": &sweep amplitudes_m is not set: mode = 'grid' needs at least one amplitude")
        return
      end if
      do k = 1, n_amp
        call need(amplitudes_m(k) >= 0.0_dp .and. amplitudes_m(k) <= huge(1.0_dp), 'amplitudes_m', k, &
                  amplitudes_m(k), '0 <= amplitudes_m (finite)')
      end do
    else
      if (n_amp > 0) then
        call fail(status, path//": &sweep amplitudes_m is set but mode = 'threshold' searches the "// &
                  "amplitude: remove amplitudes_m or use mode = 'grid'")
        return
      end if
      n_amp = 1
      ! A search ends: at most about 60 halvings from amp_max_m down to amp_tol_m.
      call need(amp_tol_m >= 1.0e-7_dp .and. amp_tol_m <= huge(1.0_dp), 'amp_tol_m', 0, amp_tol_m, &
                '1e-7 m (0.1 micrometre) <= amp_tol_m (finite)')
      call need(amp_max_m > amp_tol_m .and. amp_max_m <= 1.0e3_dp, 'amp_max_m', 0, amp_max_m, &
                'amp_tol_m = '//fmt_real(amp_tol_m)//' < amp_max_m <= 1000 m')
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
    ! Each entry in the range &arch allows for that variable (config's one rule); what
    ! depends on other variables is checked on each set's whole case below.
    do j = 1, n_kinds
      do k = 1, lengths(j)
        call need(arch_rule(param_kinds(j), lists(k, j)), trim(list_names(j)), k, lists(k, j), &
                  arch_rule_text(param_kinds(j)))
      end do
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
    if (plan%mode == 'ida') plan%n_freq_per_set = plan%records%n
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
    if (plan%mode == 'ida') then
      plan%search%amp_tol_m = scale_tol
      plan%search%amp_max_m = scale_max
      plan%search%relative_tol = .true.
    end if

    if (plan%n_samples > 0) then
      if (any(lengths > 0)) then
        call fail(status, path//': &sweep n_samples = '//itoa(n_samples)//' draws the model samples; the '// &
                  'lists ('//lengths_text(lengths)//') cannot be combined with it')
        return
      end if
      call sample_sets(path, base, n_samples, sample_seed, ranges, ranges(1, :) /= unset_real, &
                       plan%param_names, plan%param_values, plan%set_cfg, status)
      if (.not. status%ok) return
      plan%n_params = size(plan%param_names)
      plan%n_sets = n_samples
    else
      call build_sets(lists, lengths)
    end if
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
    call make_texts(lists, lengths, ranges)

  contains

    !> The records, the scale search and the sampling of mode = 'ida'.
    subroutine read_ida_part()
      integer :: v
      n_records = 0
      do k = 1, max_records
        if (len_trim(record_files(k)) == 0) exit
        n_records = k
      end do
      if (n_records == 0) then
        call fail(status, path//": &sweep record_files is not set: mode = 'ida' needs at least one record "// &
                  '(a PEER .AT2 file or a CSV with t_s, accel_m_s2)')
        return
      end if
      if (any(len_trim(record_files(n_records + 1:)) > 0)) then
        call fail(status, path//': &sweep record_files('//itoa(n_records + 1)//') is empty but a later entry '// &
                  'is set: give the list without gaps')
        return
      end if
      do k = 1, n_records
        if (scan(record_files(k), ','//achar(10)) > 0) then
          call fail(status, path//': &sweep record_files('//itoa(k)//") = '"//trim(record_files(k))// &
                    "' has a comma or a line break, which the CSV summary cannot hold: rename the file")
          return
        end if
      end do
      call need(scale_tol > 0.0_dp .and. scale_tol < 1.0_dp, 'scale_tol', 0, scale_tol, &
                '0 < scale_tol < 1 (relative width of the final bracket)')
      call need(scale_max > 0.0_dp .and. scale_max <= huge(1.0_dp), 'scale_max', 0, scale_max, 'scale_max > 0')
      call need(n_samples >= 0 .and. n_samples <= 100000, 'n_samples', 0, real(n_samples, dp), &
                '0 <= n_samples <= 100000 (0: the parameter lists, or the base case)')
      call need(sample_seed >= 0, 'sample_seed', 0, real(sample_seed, dp), 'sample_seed >= 0')
      call need(dt_check_rows >= 0, 'dt_check_rows', 0, real(dt_check_rows, dp), 'dt_check_rows >= 0')
      do v = 1, n_sampled
        if (count(ranges(:, v) /= unset_real) == 1) call fail(status, path//': &sweep '//trim(range_names(v))// &
          ' needs two values, the low and the high bound')
        if (ranges(1, v) /= unset_real .and. n_samples == 0) call fail(status, path//': &sweep '// &
          trim(range_names(v))//' is set but n_samples = 0: set n_samples to draw model samples')
      end do
      if (n_samples > 0 .and. all(ranges == unset_real)) call fail(status, path//': &sweep n_samples = '// &
        itoa(n_samples)//' but no range to sample: give one or more of '//join_words(range_names, ', '))
      if (.not. status%ok) return
      if (base%motion%waveform /= 'afd' .and. base%motion%waveform /= 'accelerogram') then
        call fail(status, path//": &motion waveform = '"//trim(base%motion%waveform)//"': mode = 'ida' "// &
                  'drives the table with each record of &sweep record_files; leave waveform unset')
        return
      end if
      call read_ida_records(path, record_files(1:n_records), plan%records, status)
      plan%n_samples = n_samples
      plan%sample_seed = sample_seed
      plan%dt_check_rows = dt_check_rows
    end subroutine read_ida_part

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
    subroutine make_texts(lists, lengths, ranges)
      real(dp), intent(in) :: lists(:, :), ranges(:, :)
      integer, intent(in) :: lengths(:)
      character(len=:), allocatable :: body
      type(config_entry_t), allocatable :: e(:)
      integer :: j
      body = "&sweep"//nl//"  mode = '"//trim(plan%mode)//"'"//nl// &
             "  combine = '"//trim(plan%combine)//"'"//nl// &
             '  pair_frequencies = '//trim(merge('.true. ', '.false.', plan%pair_frequencies))//nl
      if (plan%mode /= 'ida') body = body//'  frequencies_hz = '//fmt_exact_list(plan%frequencies_hz)//nl
      if (plan%mode == 'ida') then
        body = body//'  record_files = '
        do j = 1, plan%records%n
          body = body//"'"//trim(plan%records%given(j))//"'"//trim(merge(', ', '  ', j < plan%records%n))
        end do
        body = trim(body)//nl//'  scale_tol = '//fmt_exact_list([plan%search%amp_tol_m])//nl// &
               '  scale_max = '//fmt_exact_list([plan%search%amp_max_m])//nl// &
               '  scan_step = '//fmt_exact_list([plan%search%scan_step])//nl// &
               '  refine_factor = '//itoa(plan%search%refine_factor)//nl// &
               '  n_confirm = '//itoa(plan%search%n_confirm)//nl// &
               '  n_samples = '//itoa(plan%n_samples)//nl//'  sample_seed = '//itoa(plan%sample_seed)//nl// &
               '  dt_check_rows = '//itoa(plan%dt_check_rows)//nl
        do j = 1, n_sampled
          if (ranges(1, j) /= unset_real) body = body//'  '//trim(range_names(j))//' = '// &
                                                 fmt_exact_list(ranges(:, j))//nl
        end do
      else if (plan%mode == 'grid') then
        body = body//'  amplitudes_m = '//fmt_exact_list(plan%amplitudes_m)//nl
      else
        body = body//'  amp_tol_m = '//fmt_exact_list([plan%search%amp_tol_m])//nl// &
               '  amp_max_m = '//fmt_exact_list([plan%search%amp_max_m])//nl// &
               '  scan_step = '//fmt_exact_list([plan%search%scan_step])//nl// &
               '  refine_factor = '//itoa(plan%search%refine_factor)//nl// &
               '  n_confirm = '//itoa(plan%search%n_confirm)//nl
      end if
      do j = 1, n_kinds
        if (lengths(j) == 0) cycle
        if (j == 2) then
          body = body//'  '//trim(list_names(j))//' = '//int_list(nint(lists(1:lengths(j), j)))//nl
        else
          body = body//'  '//trim(list_names(j))//' = '//fmt_exact_list(lists(1:lengths(j), j))//nl
        end if
      end do
      plan%sweep_nml = body//'  progress_every_s = '//fmt_exact_list([plan%progress_every_s])//nl//'/'//nl
      ! The base case without what does not change results (file name, sampling).
      e = config_entries(base)
      e = pack(e, .not. (e%group == 'output' .and. (e%name == 'file' .or. e%name == 'every')))
      plan%signature = 'voussoir-sweep definition'//nl//body//'/'//nl//config_to_nml(e)
    end subroutine make_texts

  end subroutine read_sweep_plan

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
end module voussoir_sweep_plan
