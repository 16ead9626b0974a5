!> Every text helper of the kernel, the output and the drivers: lower case, lists, and
!> integers and reals as text (for people, for exact reading back, for JSON).
module voussoir_text
  use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
  use voussoir_kinds, only: dp
  implicit none
  private

  public :: lower, upper, itoa, int_list, join_words, fmt_real, fmt_fixed, fmt_significant, fmt_exact, &
            fmt_exact_list, fmt_json_real, json_string, json_bool

contains

  !> `s` in lower case (ASCII).
  pure function lower(s) result(t)
    character(len=*), intent(in) :: s
    character(len=len(s)) :: t
    integer :: i
    t = s
    do i = 1, len(s)
      if (s(i:i) >= 'A' .and. s(i:i) <= 'Z') t(i:i) = achar(iachar(s(i:i)) + 32)
    end do
  end function lower

  !> `s` in upper case (ASCII).
  pure function upper(s) result(t)
    character(len=*), intent(in) :: s
    character(len=len(s)) :: t
    integer :: i
    t = s
    do i = 1, len(s)
      if (s(i:i) >= 'a' .and. s(i:i) <= 'z') t(i:i) = achar(iachar(s(i:i)) - 32)
    end do
  end function upper

  !> An integer as text, without blanks.
  pure function itoa(i) result(text)
    integer, intent(in) :: i
    character(len=:), allocatable :: text
    character(len=16) :: buf
    write (buf, '(i0)') i
    text = trim(buf)
  end function itoa

  !> Integers as text separated by ', ' (empty for none).
  pure function int_list(values) result(text)
    integer, intent(in) :: values(:)
    character(len=:), allocatable :: text
    integer :: k
    text = ''
    do k = 1, size(values)
      if (k > 1) text = text//', '
      text = text//itoa(values(k))
    end do
  end function int_list

  !> Short readable text of a real: plain decimals for ordinary magnitudes, else
  !> scientific notation.
  function fmt_real(x) result(text)
    real(dp), intent(in) :: x
    character(len=:), allocatable :: text
    character(len=40) :: buf
    integer :: k
    if (x == 0.0_dp) then
      text = '0'
      return
    end if
    if (abs(x) >= 1.0e-4_dp .and. abs(x) < 1.0e9_dp) then
      write (buf, '(f0.9)') x
      k = len_trim(buf)
      do while (buf(k:k) == '0')
        k = k - 1
      end do
      if (buf(k:k) == '.') k = k - 1
      text = buf(:k)
      if (text(1:1) == '.') text = '0'//text
      if (text(1:2) == '-.') text = '-0'//text(2:)
    else
      write (buf, '(es14.5e3)') x  ! three exponent digits: 1.00000E-300
      text = trim(adjustl(buf))
    end if
  end function fmt_real

  !> Words joined by `sep` (', ' by default), each trimmed.
  pure function join_words(words, sep) result(text)
    character(len=*), intent(in) :: words(:)
    character(len=*), intent(in), optional :: sep
    character(len=:), allocatable :: text
    integer :: k
    text = ''
    do k = 1, size(words)
      if (k > 1) then
        if (present(sep)) then
          text = text//sep
        else
          text = text//', '
        end if
      end if
      text = text//trim(words(k))
    end do
  end function join_words

  !> `x` with `digits` decimals, and a 0 before the point.
  function fmt_fixed(x, digits) result(text)
    real(dp), intent(in) :: x
    integer, intent(in) :: digits
    character(len=:), allocatable :: text
    character(len=32) :: buf, fmt
    write (fmt, '(a,i0,a)') '(f0.', digits, ')'
    write (buf, fmt) x
    text = trim(adjustl(buf))
    if (text(1:1) == '.') text = '0'//text
    if (text(1:min(2, len(text))) == '-.') text = '-0'//text(2:)
  end function fmt_fixed

  !> A real for people: `digits` significant digits (6 by default), trailing zeros dropped.
  function fmt_significant(x, digits) result(text)
    real(dp), intent(in) :: x
    integer, intent(in), optional :: digits
    character(len=:), allocatable :: text
    character(len=40) :: buf
    character(len=16) :: fmt
    integer :: k, n_digits
    n_digits = 6
    if (present(digits)) n_digits = digits
    if (x == 0.0_dp) then
      text = '0'
      return
    end if
    if (abs(x) >= 1.0e-3_dp .and. abs(x) < 1.0e7_dp) then
      write (fmt, '(a,i0,a)') '(f0.', max(0, n_digits - 1 - floor(log10(abs(x)))), ')'
    else
      write (fmt, '(a,i0,a)') '(es0.', n_digits - 1, ')'
    end if
    write (buf, fmt) x
    text = trim(adjustl(buf))
    if (scan(text, 'eE') == 0 .and. index(text, '.') > 0) then
      k = len(text)
      do while (text(k:k) == '0')
        k = k - 1
      end do
      if (text(k:k) == '.') k = k - 1
      text = text(1:k)
    end if
    if (text(1:1) == '.') text = '0'//text
    if (text(1:2) == '-.') text = '-0'//text(2:)
  end function fmt_significant

  !> A real that reads back exactly (17 significant digits; 'nan' for NaN).
  function fmt_exact(x) result(text)
    real(dp), intent(in) :: x
    character(len=:), allocatable :: text
    character(len=32) :: buf
    if (ieee_is_nan(x)) then
      text = 'nan'
      return
    end if
    write (buf, '(es24.16)') x
    text = trim(adjustl(buf))
  end function fmt_exact

  !> Reals that read back exactly, separated by ', '.
  function fmt_exact_list(x) result(text)
    real(dp), intent(in) :: x(:)
    character(len=:), allocatable :: text
    integer :: j
    text = ''
    do j = 1, size(x)
      if (j > 1) text = text//', '
      text = text//fmt_exact(x(j))
    end do
  end function fmt_exact_list

  !> A real as a JSON number: the fewest digits (15 to 17) that read back to the same
  !> value, in E notation without padding zeros (0.376 -> 3.76E-1).
  function fmt_json_real(x) result(text)
    real(dp), intent(in) :: x
    character(len=:), allocatable :: text
    character(len=40) :: buf
    character(len=16) :: fmt
    real(dp) :: back
    integer :: digits, e, k, exponent
    if (x == 0.0_dp) then
      text = '0.0'
      return
    end if
    do digits = 15, 17
      write (fmt, '(a,i0,a)') '(es30.', digits - 1, 'e3)'
      write (buf, fmt) x
      read (buf, *) back
      if (back == x) exit
    end do
    buf = adjustl(buf)
    e = index(buf, 'E')
    read (buf(e + 1:), *) exponent
    k = e - 1
    do while (buf(k:k) == '0')
      k = k - 1
    end do
    if (buf(k:k) == '.') k = k + 1   ! keep one digit after the point
    text = buf(1:k)
    if (exponent /= 0) text = text//'E'//itoa(exponent)
  end function fmt_json_real

  !> A JSON string (escapes backslashes and quotes).
  pure function json_string(s) result(text)
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: text
    integer :: k
    text = '"'
    do k = 1, len(s)
      if (s(k:k) == achar(10)) then   ! a line break: JSON allows none raw in a string
        text = text//'\n'
        cycle
      end if
      if (s(k:k) == '"' .or. s(k:k) == '\') text = text//'\'
      text = text//s(k:k)
    end do
    text = text//'"'
  end function json_string

  pure function json_bool(x) result(text)
    logical, intent(in) :: x
    character(len=:), allocatable :: text
    if (x) then
      text = 'true'
    else
      text = 'false'
    end if
  end function json_bool

end module voussoir_text
