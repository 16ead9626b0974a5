!> Records in the ASCII format of the Engineering Strong-Motion database (ESM) and of
!> ITACA: a header of `KEY: value` lines (EVENT_NAME first; among them
!> SAMPLING_INTERVAL_S, NDATA, UNITS, DATA_TYPE, STATION_CODE, STREAM, USER1..USER5),
!> then NDATA samples, one or more a line.
!>
!> The unit of the samples is the header's UNITS (ESM and ITACA write `cm/s^2`); a file
!> without it, or with a unit that is not an acceleration's, is refused with a message
!> that says how to state it. DATA_TYPE, where given, must be an acceleration.
module voussoir_esm_record
  use voussoir_kinds, only: dp, g_m_s2
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: lower, upper, itoa
  use voussoir_numeric_csv, only: parse_number, number_ok, number_not_finite
  implicit none
  private

  public :: read_esm, esm_unit_m_s2

  integer, parameter :: line_len = 4096
  !> The units an ESM file may state, as they are written (spaces dropped, any case).
  character(len=*), parameter :: known_units = "'cm/s^2' (or cm/s2, gal), 'm/s^2' (or m/s2), 'mm/s^2', 'g'"

  !> What the header says of the samples and where they come from.
  type :: esm_header_t
    real(dp) :: dt_s = 0.0_dp                 !! SAMPLING_INTERVAL_S
    integer :: npts = -1                      !! NDATA (-1: not given)
    character(len=512) :: units = ''         !! UNITS as written
    integer :: units_line = 0                 !! its line (0: none)
    character(len=512) :: event = '', station = '', stream = ''
  end type esm_header_t

contains

  !> The samples [m/s2] of the ESM file `path`, their interval [s] and a description
  !> (event, station and stream, as the header names them).
  subroutine read_esm(path, dt_s, accel_m_s2, description, status)
    character(len=*), intent(in) :: path
    real(dp), intent(out) :: dt_s
    real(dp), allocatable, intent(out) :: accel_m_s2(:)
    character(len=*), intent(out) :: description
    type(status_t), intent(inout) :: status
    character(len=line_len) :: line
    character(len=512) :: iomsg, key, value_text
    integer :: unit, ios, line_no, colon, n, header_end
    real(dp) :: to_m_s2
    type(esm_header_t) :: h

    dt_s = 0.0_dp
    description = ''
    allocate (accel_m_s2(0))
    open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      call fail(status, trim(path)//': cannot open: '//trim(iomsg))
      return
    end if
    line_no = 0
    ! The header: every line with a colon, up to the first sample.
    do
      read (unit, '(a)', iostat=ios) line
      if (ios /= 0) exit
      line_no = line_no + 1
      colon = index(line, ':')
      if (colon == 0) then
        if (len_trim(line) == 0) cycle
        exit
      end if
      key = upper(adjustl(line(:colon - 1)))
      value_text = adjustl(line(colon + 1:))
      if (line_no == 1 .and. key /= 'EVENT_NAME') then
        call fail(status, trim(path)//":1: an ESM/ITACA file starts with 'EVENT_NAME:'")
        exit
      end if
      call header_entry(path, line_no, key, value_text, h, status)
      if (.not. status%ok) exit
    end do
    header_end = line_no
    if (ios == 0) header_end = line_no - 1   ! the last line read is the first sample
    if (status%ok) call check_header(path, header_end, h, to_m_s2, status)
    if (.not. status%ok) then
      close (unit)
      return
    end if
    dt_s = h%dt_s
    deallocate (accel_m_s2)
    allocate (accel_m_s2(h%npts))
    ! The samples: the line read last (if any) and those after it.
    n = 0
    if (ios == 0) then
      do
        call take_samples(path, line, line_no, accel_m_s2, n, status)
        if (.not. status%ok) exit
        read (unit, '(a)', iostat=ios) line
        if (ios /= 0) exit
        line_no = line_no + 1
      end do
    end if
    close (unit)
    if (status%ok .and. n < h%npts) &
      call fail(status, trim(path)//':'//itoa(line_no)//': the file ends after '//itoa(n)// &
                ' samples, but NDATA = '//itoa(h%npts)//' in the header')
    accel_m_s2 = accel_m_s2*to_m_s2
    description = trim(h%event)
    if (len_trim(h%station) > 0) description = trim(description)//', station '//trim(h%station)
    if (len_trim(h%stream) > 0) description = trim(description)//' '//trim(h%stream)
  end subroutine read_esm

  !> One header line `key: value_text` (line `line_no` of `path`) into `h`.
  subroutine header_entry(path, line_no, key, value_text, h, status)
    character(len=*), intent(in) :: path, key, value_text
    integer, intent(in) :: line_no
    type(esm_header_t), intent(inout) :: h
    type(status_t), intent(inout) :: status
    integer :: kind
    real(dp) :: value
    select case (key)
    case ('EVENT_NAME')
      h%event = value_text
    case ('STATION_CODE')
      h%station = value_text
    case ('STREAM')
      h%stream = value_text
    case ('SAMPLING_INTERVAL_S')
      call parse_number(value_text, h%dt_s, kind)
      if (kind /= number_ok .or. .not. h%dt_s > 0.0_dp) then
        call fail(status, trim(path)//':'//itoa(line_no)//": SAMPLING_INTERVAL_S = '"//trim(value_text)// &
                  "' is not a time step > 0 (s)")
        return
      end if
    case ('NDATA')
      call parse_number(value_text, value, kind)
      if (kind /= number_ok .or. value /= aint(value) .or. value < 2.0_dp .or. value > real(huge(1), dp)) then
        call fail(status, trim(path)//':'//itoa(line_no)//": NDATA = '"//trim(value_text)// &
                  "' is not an integer >= 2")
        return
      end if
      h%npts = int(value)
    case ('UNITS')
      h%units = value_text
      h%units_line = line_no
    case ('DATA_TYPE')
      if (len_trim(value_text) > 0 .and. index(upper(value_text), 'ACCELERATION') == 0) then
        call fail(status, trim(path)//':'//itoa(line_no)//": DATA_TYPE = '"//trim(value_text)// &
                  "': a ground-motion record for the table must be an ACCELERATION")
        return
      end if
    end select
  end subroutine header_entry

  !> The numbers of `text` (line `at` of `path`) stored after the `n` samples taken.
  subroutine take_samples(path, text, at, samples, n, status)
    character(len=*), intent(in) :: path, text
    integer, intent(in) :: at
    real(dp), intent(inout) :: samples(:)
    integer, intent(inout) :: n
    type(status_t), intent(inout) :: status
    character(len=*), parameter :: separators = ' ,'//achar(9)//achar(13)
    integer :: start, finish, kind
    real(dp) :: sample
    finish = 0
    do
      start = verify(text(finish + 1:), separators)
      if (start == 0) exit
      start = finish + start
      finish = scan(text(start:), separators)
      if (finish == 0) then
        finish = len(text)
      else
        finish = start + finish - 2
      end if
      call parse_number(text(start:finish), sample, kind)
      if (kind /= number_ok) then
        call fail(status, trim(path)//':'//itoa(at)//": '"//text(start:finish)//"' is "// &
                  merge('not a finite number', 'not a number       ', kind == number_not_finite))
        return
      end if
      n = n + 1
      if (n > size(samples)) then
        call fail(status, trim(path)//':'//itoa(at)//': more samples than NDATA = '//itoa(size(samples))// &
                  ' in the header')
        return
      end if
      samples(n) = sample
    end do
  end subroutine take_samples

  !> The header of `path` (lines 1 to `header_end`) gave the interval, the count and a
  !> known unit (`to_m_s2`, the factor from it to m/s2).
  subroutine check_header(path, header_end, h, to_m_s2, status)
    character(len=*), intent(in) :: path
    integer, intent(in) :: header_end
    type(esm_header_t), intent(in) :: h
    real(dp), intent(out) :: to_m_s2
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: lines
    to_m_s2 = 0.0_dp
    lines = ' (lines 1-'//itoa(header_end)//')'
    if (.not. h%dt_s > 0.0_dp) then
      call fail(status, trim(path)//': no SAMPLING_INTERVAL_S in the header'//lines)
    else if (h%npts < 0) then
      call fail(status, trim(path)//': no NDATA in the header'//lines)
    else if (h%units_line == 0 .or. len_trim(h%units) == 0) then
      call fail(status, trim(path)//': the unit of the samples cannot be determined: the header'//lines// &
                " has no UNITS; state it in a header line such as 'UNITS: cm/s^2' (known: "//known_units//')')
    else
      to_m_s2 = esm_unit_m_s2(h%units)
      if (to_m_s2 == 0.0_dp) &
        call fail(status, trim(path)//':'//itoa(h%units_line)//": UNITS = '"//trim(h%units)// &
                  "' is not a unit of acceleration known here; state one of "//known_units)
    end if
  end subroutine check_header

  !> The factor from the acceleration unit `units` (as an ESM header writes it) to m/s2;
  !> 0 for a unit not known.
  pure real(dp) function esm_unit_m_s2(units)
    character(len=*), intent(in) :: units
    character(len=len(units)) :: u
    integer :: k, j
    u = ''
    j = 0
    do k = 1, len_trim(units)
      if (units(k:k) == ' ') cycle
      j = j + 1
      u(j:j) = units(k:k)
    end do
    select case (lower(trim(u)))
    case ('cm/s^2', 'cm/s2', 'cm/s**2', 'cm/sec^2', 'cm/sec2', 'gal')
      esm_unit_m_s2 = 0.01_dp
    case ('mm/s^2', 'mm/s2', 'mm/s**2')
      esm_unit_m_s2 = 0.001_dp
    case ('m/s^2', 'm/s2', 'm/s**2', 'm/sec^2', 'm/sec2')
      esm_unit_m_s2 = 1.0_dp
    case ('g')
      esm_unit_m_s2 = g_m_s2
    case default
      esm_unit_m_s2 = 0.0_dp
    end select
  end function esm_unit_m_s2

end module voussoir_esm_record
