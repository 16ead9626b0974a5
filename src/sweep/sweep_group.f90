!> The &sweep group as written in the input: its variables, their defaults and the
!> sentinels of unset list entries, and the mechanics of reading it (check the names and
!> list lengths, open, read the group, end of file) with the range check `need` and the
!> list checks the plan and the modes share. The one place that reads &sweep; what the
!> values mean is src/sweep/sweep_plan.f90 and the mode files.
module voussoir_sweep_group
  use, intrinsic :: iso_fortran_env, only: iostat_end
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: fmt_real
  use voussoir_namelist_check, only: check_names, check_list_lengths
  use voussoir_threshold_search, only: threshold_settings_t
  use voussoir_sweep_ida, only: n_sampled, range_names
  implicit none
  private

  public :: sweep_group_t, read_sweep_group, need, list_length, lengths_text
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

  !> The values of &sweep as given, defaults where not (docs/sweep.md has the table).
  type :: sweep_group_t
    character(len=16) :: mode = ''                 !! the caller sets the default mode
    character(len=16) :: combine = 'product'
    logical :: pair_frequencies = .false.
    real(dp) :: frequencies_hz(max_list) = unset_real
    real(dp) :: amplitudes_m(max_list) = unset_real
    type(threshold_settings_t) :: search            !! amp_tol_m, amp_max_m, scan_step, refine_factor, n_confirm
    real(dp) :: progress_every_s = 10.0_dp
    real(dp) :: lists(max_list, n_kinds) = unset_real   !! the swept lists, in the order of param_kinds
    character(len=record_len) :: record_files(max_records) = ''
    real(dp) :: scale_tol = 0.05_dp
    real(dp) :: scale_max = 20.0_dp
    integer :: n_samples = 0
    integer :: sample_seed = 1
    integer :: dt_check_rows = 0
    real(dp) :: ranges(2, n_sampled) = unset_real   !! low and high bound of each sampled variable
  end type sweep_group_t

contains

  !> Read the &sweep group of `path` into `group`, whose values are the defaults.
  subroutine read_sweep_group(path, group, status)
    character(len=*), intent(in) :: path
    type(sweep_group_t), intent(inout) :: group
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
    integer :: unit, ios
    character(len=512) :: iomsg

    associate (g => group)
      mode = g%mode
      combine = g%combine
      pair_frequencies = g%pair_frequencies
      frequencies_hz = g%frequencies_hz
      amplitudes_m = g%amplitudes_m
      amp_tol_m = g%search%amp_tol_m
      amp_max_m = g%search%amp_max_m
      scan_step = g%search%scan_step
      refine_factor = g%search%refine_factor
      n_confirm = g%search%n_confirm
      progress_every_s = g%progress_every_s
      embrace_list_deg = g%lists(:, 1)
      n_voussoirs_list = unset_int
      thickness_list_m = g%lists(:, 3)
      friction_list = g%lists(:, 4)
      contact_inset_list_m = g%lists(:, 5)
      record_files = g%record_files
      scale_tol = g%scale_tol
      scale_max = g%scale_max
      n_samples = g%n_samples
      sample_seed = g%sample_seed
      dt_check_rows = g%dt_check_rows
      friction_range = g%ranges(:, 1)
      contact_inset_range_m = g%ranges(:, 2)
      thickness_range_m = g%ranges(:, 3)
      size_imperfection_range = g%ranges(:, 4)
    end associate

    call check_sweep_names(path, status)
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

    associate (g => group)
      g%mode = mode
      g%combine = combine
      g%pair_frequencies = pair_frequencies
      g%frequencies_hz = frequencies_hz
      g%amplitudes_m = amplitudes_m
      g%search%amp_tol_m = amp_tol_m
      g%search%amp_max_m = amp_max_m
      g%search%scan_step = scan_step
      g%search%refine_factor = refine_factor
      g%search%n_confirm = n_confirm
      g%progress_every_s = progress_every_s
      g%lists(:, 1) = embrace_list_deg
      g%lists(:, 2) = merge(real(n_voussoirs_list, dp), unset_real, n_voussoirs_list /= unset_int)
      g%lists(:, 3) = thickness_list_m
      g%lists(:, 4) = friction_list
      g%lists(:, 5) = contact_inset_list_m
      g%record_files = record_files
      g%scale_tol = scale_tol
      g%scale_max = scale_max
      g%n_samples = n_samples
      g%sample_seed = sample_seed
      g%dt_check_rows = dt_check_rows
      g%ranges = reshape([friction_range, contact_inset_range_m, thickness_range_m, size_imperfection_range], &
                         [2, n_sampled])
    end associate
  end subroutine read_sweep_group

  !> The names in the &sweep group of `path` are its variables, and no list is given
  !> more entries than it holds.
  subroutine check_sweep_names(path, status)
    character(len=*), intent(in) :: path
    type(status_t), intent(inout) :: status
    call check_names(path, 'sweep', [character(len=24) :: 'mode', 'combine', 'pair_frequencies', &
      'frequencies_hz', 'amplitudes_m', 'amp_tol_m', 'amp_max_m', 'scan_step', 'refine_factor', 'n_confirm', &
      'progress_every_s', list_names, 'record_files', 'scale_tol', 'scale_max', 'n_samples', 'sample_seed', &
      range_names, 'dt_check_rows'], status)
    call check_list_lengths(path, 'sweep', [character(len=24) :: 'frequencies_hz', 'amplitudes_m', list_names, &
      'record_files', range_names], [max_list, max_list, spread(max_list, 1, n_kinds), max_records, &
      spread(2, 1, size(range_names))], status)
  end subroutine check_sweep_names

  !> Unless `status` already failed: fail with the standard range message of &sweep
  !> `name`(`index`, if > 0) = `value` when not `good`.
  subroutine need(status, path, good, name, index, value, allowed)
    type(status_t), intent(inout) :: status
    character(len=*), intent(in) :: path, name, allowed
    logical, intent(in) :: good
    integer, intent(in) :: index
    real(dp), intent(in) :: value
    character(len=16) :: idx
    if (good .or. .not. status%ok) return
    idx = ''
    if (index > 0) write (idx, '(a,i0,a)') '(', index, ')'
    call fail(status, path//': &sweep '//name//trim(idx)//' = '//fmt_real(value)// &
              ' is outside the allowed range '//allowed)
  end subroutine need

  !> Entries set from the start of the &sweep list `x`, with no gap (a gap fails `status`).
  integer function list_length(status, path, x, name) result(n)
    type(status_t), intent(inout) :: status
    character(len=*), intent(in) :: path
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

  !> "list n, ..." of the swept lists given (`n`: their lengths, 0 for unset).
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

end module voussoir_sweep_group
