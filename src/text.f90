!> Small text helpers shared by the kernel and the drivers: lower case, integers and
!> reals as short readable text.
module voussoir_text
  use voussoir_kinds, only: dp
  implicit none
  private

  public :: lower, itoa, int_list, fmt_real

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
      write (buf, '(es12.5)') x
      text = trim(adjustl(buf))
    end if
  end function fmt_real

end module voussoir_text
