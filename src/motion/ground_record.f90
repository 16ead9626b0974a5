!> Ground-motion records (accelerograms) and their intensity measures.
!>
!> Two formats, chosen by the file name's extension:
!> - `.AT2` (any case): a PEER NGA strong-motion file in units of g. Four header lines:
!>   title, event and station, units ("... IN UNITS OF G", required), and NPTS and DT in either
!>   of the two variants PEER has written, "NPTS=   5372, DT=   .0100 SEC" (NGA-West2)
!>   or "  4000    0.01000   NPTS, DT" (the older database); then NPTS numbers, any
!>   number of them per line.
!> - `.csv`: columns `t_s` and `accel_m_s2` (docs/measured_data.md's CSV rules),
!>   uniformly sampled, time increasing.
!> - `.asc` (any case): an ESM or ITACA ASCII file, in the unit its header's UNITS names
!>   (cm/s^2 as those databases write it; src/motion/esm_record.f90).
!> A record that breaks a rule is refused with the file and the line.
!>
!> The acceleration between samples is the linear interpolation of the samples; the
!> velocity and the displacement are its exact integrals from rest (piecewise quadratic
!> and cubic), so the intensity measures below are exact for that acceleration.
module voussoir_ground_record
  use voussoir_kinds, only: dp, pi, g_m_s2
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: lower, upper, itoa, fmt_real
  use voussoir_numeric_csv, only: read_csv_columns, parse_number, number_ok, number_not_finite
  use voussoir_esm_record, only: read_esm
  implicit none
  private

  public :: ground_record_t, record_intensity_t, read_ground_record, record_intensity
  public :: integrate_linear_accel, record_stem

  integer, parameter :: text_len = 512
  !> Relative departure of a CSV time step from the first one that still counts as uniform.
  real(dp), parameter :: uniform_step_tol = 1.0e-3_dp

  !> A record as read: the samples in m/s2 (unscaled), the first one at its own time 0.
  type :: ground_record_t
    character(len=text_len) :: path = ''
    character(len=text_len) :: name = ''         !! the file name without folder and extension
    character(len=text_len) :: description = '' !! an AT2 file's event and station line; an ESM file's event, station, stream
    real(dp) :: dt_s = 0.0_dp
    real(dp), allocatable :: accel_m_s2(:)
  end type ground_record_t

  !> Intensity measures of an acceleration history, linear between its samples.
  type :: record_intensity_t
    real(dp) :: pga_m_s2 = 0.0_dp                !! peak |a|
    real(dp) :: pgv_m_s = 0.0_dp                 !! peak |v|, v the exact integral from rest
    real(dp) :: arias_m_s = 0.0_dp               !! pi/(2 g) times the integral of a^2
    real(dp) :: t5_s = 0.0_dp, t95_s = 0.0_dp    !! 5 % and 95 % of the Arias intensity, from the first sample
    real(dp) :: significant_duration_s = 0.0_dp  !! t95 - t5
  end type record_intensity_t

contains

  !> Read the record `path` (.AT2 or .csv).
  subroutine read_ground_record(path, rec, status)
    character(len=*), intent(in) :: path
    type(ground_record_t), intent(out) :: rec
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: ext
    integer :: k

    rec%path = path
    rec%name = record_stem(path)
    k = index(path, '.', back=.true.)
    ext = ''
    if (k > index(path, '/', back=.true.)) ext = lower(path(k + 1:))
    select case (ext)
    case ('at2')
      call read_at2(path, rec, status)
    case ('csv')
      call read_accel_csv(path, rec, status)
    case ('asc')
      call read_esm(path, rec%dt_s, rec%accel_m_s2, rec%description, status)
    case default
      call fail(status, trim(path)//": unknown record format '."//ext// &
                "' (expected a PEER NGA .AT2 file in g, a .csv with columns t_s, accel_m_s2, or an ESM/ITACA "// &
                ".ASC file with its UNITS in the header)")
    end select
  end subroutine read_ground_record

  !> The file name of `path` without its folder and its last extension.
  pure function record_stem(path) result(stem)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: stem
    integer :: k
    stem = trim(path(index(path, '/', back=.true.) + 1:))
    k = index(stem, '.', back=.true.)
    if (k > 1) stem = stem(:k - 1)
  end function record_stem

  !> A PEER NGA .AT2 file (units of g) into m/s2.
  subroutine read_at2(path, rec, status)
    character(len=*), intent(in) :: path
    type(ground_record_t), intent(inout) :: rec
    type(status_t), intent(inout) :: status
    character(len=text_len) :: header(4)
    character(len=512) :: iomsg
    integer :: unit, ios, line_no, npts
    real(dp) :: dt

    open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      call fail(status, trim(path)//': cannot open: '//trim(iomsg))
      return
    end if
    do line_no = 1, 4
      read (unit, '(a)', iostat=ios) header(line_no)
      if (ios /= 0) then
        call fail(status, trim(path)//':'//itoa(line_no)//': the file ends inside the four header '// &
                  'lines of a PEER .AT2 file (title, event, units, NPTS and DT)')
        close (unit)
        return
      end if
    end do
    rec%description = adjustl(header(2))
    call check_at2_units(path, header(3), status)
    if (status%ok) call at2_npts_dt(path, header(4), npts, dt, status)
    if (.not. status%ok) then
      close (unit)
      return
    end if
    allocate (rec%accel_m_s2(npts))
    call read_at2_samples(unit, path, rec%accel_m_s2, status)
    close (unit)
    rec%dt_s = dt
  end subroutine read_at2

  !> The `size(accel_m_s2)` samples [m/s2] that follow the header of the AT2 file `path`
  !> open on `unit`, any number of them a line (in g in the file).
  subroutine read_at2_samples(unit, path, accel_m_s2, status)
    integer, intent(in) :: unit
    character(len=*), intent(in) :: path
    real(dp), intent(out) :: accel_m_s2(:)
    type(status_t), intent(inout) :: status
    character(len=*), parameter :: separators = ' ,'//achar(9)//achar(13)
    character(len=4096) :: line
    integer :: ios, line_no, npts, n, start, finish, kind
    real(dp) :: value

    npts = size(accel_m_s2)
    n = 0
    line_no = 4
    do
      read (unit, '(a)', iostat=ios) line
      if (ios /= 0) exit
      line_no = line_no + 1
      finish = 0
      do
        start = verify(line(finish + 1:), separators)
        if (start == 0) exit
        start = finish + start
        finish = scan(line(start:), separators)
        if (finish == 0) then
          finish = len(line)
        else
          finish = start + finish - 2
        end if
        call parse_number(line(start:finish), value, kind)
        if (kind /= number_ok) then
          call fail(status, trim(path)//':'//itoa(line_no)//": '"//line(start:finish)//"' is "// &
                    merge('not a finite number', 'not a number       ', kind == number_not_finite))
          exit
        end if
        n = n + 1
        if (n > npts) then
          call fail(status, trim(path)//':'//itoa(line_no)//': more samples than NPTS = '//itoa(npts)// &
                    ' in the header (line 4)')
          exit
        end if
        accel_m_s2(n) = value*g_m_s2
      end do
      if (.not. status%ok) exit
    end do
    if (status%ok .and. n < npts) &
      call fail(status, trim(path)//':'//itoa(line_no)//': the file ends after '//itoa(n)// &
                ' samples, but NPTS = '//itoa(npts)//' in the header (line 4)')
  end subroutine read_at2_samples

  !> Line 3 of the AT2 file `path` names the units; a line that names none, or anything
  !> but g, is refused (the unit cannot be taken for granted).
  subroutine check_at2_units(path, text, status)
    character(len=*), intent(in) :: path, text
    type(status_t), intent(inout) :: status
    character(len=len(text)) :: up
    integer :: k
    up = upper(text)
    k = index(up, 'UNITS OF')
    if (k == 0) then
      call fail(status, trim(path)//":3: the line '"//trim(text)//"' names no units, so the unit of the samples "// &
                "cannot be determined: a PEER .AT2 record states it there, as 'ACCELERATION TIME SERIES IN UNITS OF G'")
      return
    end if
    up = adjustl(up(k + 8:))
    if (up(1:1) == 'G' .and. (up(2:2) == ' ' .or. up(2:2) == ',' .or. up(2:2) == '.')) return
    call fail(status, trim(path)//":3: units '"//trim(up)//"': a PEER .AT2 record must be in units of g")
  end subroutine check_at2_units

  !> NPTS and DT of the fourth header line of the AT2 file `path`, in either PEER variant.
  subroutine at2_npts_dt(path, text, npts, dt, status)
    character(len=*), intent(in) :: path, text
    integer, intent(out) :: npts
    real(dp), intent(out) :: dt
    type(status_t), intent(inout) :: status
    character(len=len(text)) :: up
    character(len=64) :: word(2)
    integer :: k, ios
    real(dp) :: count
    up = upper(text)
    npts = 0
    dt = 0.0_dp
    word = ''
    k = index(up, 'NPTS=')
    if (k > 0) then
      word(1) = first_word(up(k + 5:))
      k = index(up, 'DT=')
      if (k == 0) then
        call fail(status, trim(path)//":4: no 'DT=' in the header line '"//trim(text)//"'")
        return
      end if
      word(2) = first_word(up(k + 3:))
    else
      k = index(up, 'NPTS')
      if (k == 0) then
        call fail(status, trim(path)//":4: no NPTS in the header line '"//trim(text)// &
                  "' (expected 'NPTS= n, DT= dt SEC' or 'n dt NPTS, DT')")
        return
      end if
      if (index(up(k:), 'DT') == 0) then
        call fail(status, trim(path)//":4: no DT in the header line '"//trim(text)// &
                  "' (expected 'n dt NPTS, DT')")
        return
      end if
      read (up(:k - 1), *, iostat=ios) word
      if (ios /= 0) then
        call fail(status, trim(path)//":4: the header line '"//trim(text)// &
                  "' lacks the values before 'NPTS, DT'")
        return
      end if
    end if
    call parse_number(word(1), count, k)
    if (k /= number_ok .or. count /= aint(count) .or. count < 2.0_dp .or. count > real(huge(1), dp)) then
      call fail(status, trim(path)//":4: NPTS = '"//trim(word(1))//"' is not an integer >= 2")
      return
    end if
    npts = int(count)
    call parse_number(word(2), dt, k)
    if (k /= number_ok .or. .not. dt > 0.0_dp) then
      call fail(status, trim(path)//":4: DT = '"//trim(word(2))//"' is not a time step > 0 (s)")
      return
    end if
  end subroutine at2_npts_dt

  !> The first blank- or comma-delimited word of `text`.
  pure function first_word(text) result(word)
    character(len=*), intent(in) :: text
    character(len=64) :: word
    integer :: k
    word = adjustl(text)
    k = scan(word, ' ,')
    if (k > 0) word = word(:k - 1)
  end function first_word


  !> A CSV record: columns t_s and accel_m_s2, uniformly sampled, time increasing.
  subroutine read_accel_csv(path, rec, status)
    character(len=*), intent(in) :: path
    type(ground_record_t), intent(inout) :: rec
    type(status_t), intent(inout) :: status
    real(dp), allocatable :: columns(:, :)
    integer, allocatable :: lines(:)
    real(dp) :: step0, step
    integer :: n, i

    call read_csv_columns(path, [character(len=16) :: 't_s', 'accel_m_s2'], columns, lines, status)
    if (.not. status%ok) return
    n = size(lines)
    if (n < 2) then
      call fail(status, trim(path)//': a record needs at least 2 samples, found '//itoa(n))
      return
    end if
    step0 = columns(1, 2) - columns(1, 1)
    do i = 2, n
      step = columns(1, i) - columns(1, i - 1)
      if (.not. step > 0.0_dp) then
        call fail(status, trim(path)//':'//itoa(lines(i))//': t_s = '//fmt_real(columns(1, i))// &
                  ' does not increase (the row before has t_s = '//fmt_real(columns(1, i - 1))//')')
        return
      end if
      if (abs(step - step0) > uniform_step_tol*step0) then
        call fail(status, trim(path)//':'//itoa(lines(i))//': the time step '//fmt_real(step)// &
                  ' s differs from the first one, '//fmt_real(step0)//' s (a record must be uniformly sampled)')
        return
      end if
    end do
    rec%dt_s = (columns(1, n) - columns(1, 1))/(n - 1)
    rec%accel_m_s2 = columns(2, :)
  end subroutine read_accel_csv

  !> Velocity and displacement at the samples of an acceleration that is linear between
  !> samples `dt_s` apart, integrated exactly from rest (v = x = 0 at the first sample).
  pure subroutine integrate_linear_accel(a, dt_s, v, x)
    real(dp), intent(in) :: a(:), dt_s
    real(dp), intent(out) :: v(size(a)), x(size(a))
    integer :: i
    v(1) = 0.0_dp
    x(1) = 0.0_dp
    do i = 1, size(a) - 1
      v(i + 1) = v(i) + 0.5_dp*dt_s*(a(i) + a(i + 1))
      x(i + 1) = x(i) + dt_s*v(i) + dt_s*dt_s*(2.0_dp*a(i) + a(i + 1))/6.0_dp
    end do
  end subroutine integrate_linear_accel

  !> PGA, PGV, Arias intensity and significant duration (5-95 %) of the acceleration
  !> `a` [m/s2], linear between samples `dt_s` apart, starting from rest.
  pure function record_intensity(a, dt_s) result(im)
    real(dp), intent(in) :: a(:), dt_s
    type(record_intensity_t) :: im
    real(dp) :: v(size(a)), x(size(a)), cum(size(a)), tau, slope
    integer :: i, n

    n = size(a)
    im%pga_m_s2 = maxval(abs(a))
    call integrate_linear_accel(a, dt_s, v, x)
    im%pgv_m_s = maxval(abs(v))
    ! Inside a segment where a changes sign, v has its extremum.
    do i = 1, n - 1
      if (a(i)*a(i + 1) < 0.0_dp) then
        tau = dt_s*a(i)/(a(i) - a(i + 1))
        slope = (a(i + 1) - a(i))/dt_s
        im%pgv_m_s = max(im%pgv_m_s, abs(v(i) + a(i)*tau + 0.5_dp*slope*tau*tau))
      end if
    end do
    ! Cumulative integral of a^2 at the samples (exact for linear a).
    cum(1) = 0.0_dp
    do i = 1, n - 1
      cum(i + 1) = cum(i) + dt_s*(a(i)**2 + a(i)*a(i + 1) + a(i + 1)**2)/3.0_dp
    end do
    im%arias_m_s = pi/(2.0_dp*g_m_s2)*cum(n)
    if (cum(n) > 0.0_dp) then
      im%t5_s = crossing(0.05_dp*cum(n))
      im%t95_s = crossing(0.95_dp*cum(n))
    end if
    im%significant_duration_s = im%t95_s - im%t5_s

  contains

    !> The time at which the integral of a^2 reaches `target` (bisection on the cubic
    !> of the segment, to round-off).
    pure real(dp) function crossing(target)
      real(dp), intent(in) :: target
      real(dp) :: lo, hi, mid, s
      integer :: k, it
      k = 1
      do while (k < n - 1 .and. cum(k + 1) < target)
        k = k + 1
      end do
      s = (a(k + 1) - a(k))/dt_s
      lo = 0.0_dp
      hi = dt_s
      do it = 1, 200
        mid = 0.5_dp*(lo + hi)
        if (mid <= lo .or. mid >= hi) exit
        if (cum(k) + a(k)**2*mid + a(k)*s*mid**2 + s*s*mid**3/3.0_dp < target) then
          lo = mid
        else
          hi = mid
        end if
      end do
      crossing = (k - 1)*dt_s + 0.5_dp*(lo + hi)
    end function crossing

  end function record_intensity

end module voussoir_ground_record
