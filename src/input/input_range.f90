!> The allowed range of an input value, and the one message for a value outside it:
!> "<file>: &group name = value is outside the allowed range <range>".
!>
!> A range is written once, as the user reads it ('0 < dt_s <= 0.1', '1e-4 m <=
!> block_width_m <= 100 m', 'friction >= 0 (finite)', 'ramp_rate_m_s3 /= 0'), and its
!> bounds are read from that text, so the check and its message cannot disagree.
!> '(finite)' bounds the value by the largest real; any other note in ( ) is words only.
module voussoir_input_range
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: fmt_real, itoa
  implicit none
  private

  public :: range_t, range_of, in_range, need, need_range

  !> Bounds read from a range text: low (<, <=) and high (<, <=) or not zero (/=).
  type :: range_t
    character(len=:), allocatable :: text  !! as written; '' for no range
    logical :: valid = .true.              !! the text could be read (a programming error if not)
    logical :: has_low = .false., low_strict = .false.
    logical :: has_high = .false., high_strict = .false.
    logical :: nonzero = .false.
    real(dp) :: low = 0.0_dp, high = 0.0_dp
  end type range_t

  !> Fail `status` (unless it already failed) when `good` is false.
  interface need
    module procedure need_real, need_integer, need_text
  end interface need

  !> Fail `status` (unless it already failed) when `value` is outside the range text
  !> `allowed` of `name` (its index, as in 'x(2)', aside): a range that does not depend on
  !> other variables, checked outside a group's table. `note`, if given, follows the
  !> range in the message (whose range it is, why).
  interface need_range
    module procedure need_range_real, need_range_integer
  end interface need_range

contains

  !> The range `text` of variable `name`: `[low <|<= [unit]] name [op bound [unit]] [(note)]`.
  function range_of(text, name) result(r)
    character(len=*), intent(in) :: text, name
    type(range_t) :: r
    character(len=32) :: words(12)
    integer :: n, at
    real(dp) :: bound

    r%text = text
    call split_words(text, words, n)
    at = findloc(words(:n), name, dim=1)
    r%valid = at > 0
    if (.not. r%valid) return
    if (index(text, '(finite)') > 0) then   ! no bound above but the largest real
      r%has_high = .true.
      r%high = huge(1.0_dp)
    end if
    if (at > 1) then
      r%has_low = .true.
      r%low_strict = words(at - 1) == '<'
      r%valid = (words(at - 1) == '<' .or. words(at - 1) == '<=') .and. number(words(1), r%low)
    end if
    if (at < n .and. r%valid) then
      if (words(at + 1)(1:1) == '(') return   ! a note only
      r%valid = at + 1 < n
      if (.not. r%valid) return
      r%valid = number(words(at + 2), bound)
      select case (words(at + 1))
      case ('<', '<=')
        r%has_high = .true.
        r%high_strict = words(at + 1) == '<'
        r%high = bound
      case ('>', '>=')
        r%has_low = .true.
        r%low_strict = words(at + 1) == '>'
        r%low = bound
      case ('/=')
        r%nonzero = .true.
        r%valid = r%valid .and. bound == 0.0_dp
      case default
        r%valid = .false.
      end select
    end if
  end function range_of

  !> The first blank-separated words of `text` (at most size(words)).
  pure subroutine split_words(text, words, n)
    character(len=*), intent(in) :: text
    character(len=*), intent(out) :: words(:)
    integer, intent(out) :: n
    integer :: i, start
    words = ''
    n = 0
    i = 1
    do while (i <= len(text) .and. n < size(words))
      if (text(i:i) == ' ') then
        i = i + 1
        cycle
      end if
      start = i
      do while (i <= len(text))
        if (text(i:i) == ' ') exit
        i = i + 1
      end do
      n = n + 1
      words(n) = text(start:i - 1)
    end do
  end subroutine split_words

  logical function number(word, x)
    character(len=*), intent(in) :: word
    real(dp), intent(out) :: x
    integer :: ios
    read (word, *, iostat=ios) x
    number = ios == 0
  end function number

  !> Whether `x` lies in range `r` (no range: any value).
  pure logical function in_range(r, x)
    type(range_t), intent(in) :: r
    real(dp), intent(in) :: x
    in_range = .true.
    if (r%has_low) in_range = merge(x > r%low, x >= r%low, r%low_strict)
    if (r%has_high) in_range = in_range .and. merge(x < r%high, x <= r%high, r%high_strict)
    if (r%nonzero) in_range = x /= 0.0_dp
  end function in_range

  subroutine need_real(good, file, group, name, value, allowed, status)
    logical, intent(in) :: good
    character(len=*), intent(in) :: file, group, name, allowed
    real(dp), intent(in) :: value
    type(status_t), intent(inout) :: status
    if (good .or. .not. status%ok) return
    call fail(status, outside(file, group, name, fmt_real(value), allowed))
  end subroutine need_real

  subroutine need_integer(good, file, group, name, value, allowed, status)
    logical, intent(in) :: good
    character(len=*), intent(in) :: file, group, name, allowed
    integer, intent(in) :: value
    type(status_t), intent(inout) :: status
    if (good .or. .not. status%ok) return
    call fail(status, outside(file, group, name, itoa(value), allowed))
  end subroutine need_integer

  subroutine need_text(good, file, group, name, value, allowed, status)
    logical, intent(in) :: good
    character(len=*), intent(in) :: file, group, name, value, allowed
    type(status_t), intent(inout) :: status
    if (good .or. .not. status%ok) return
    call fail(status, outside(file, group, name, "'"//trim(value)//"'", allowed))
  end subroutine need_text

  subroutine need_range_real(allowed, file, group, name, value, status, note)
    character(len=*), intent(in) :: allowed, file, group, name
    real(dp), intent(in) :: value
    type(status_t), intent(inout) :: status
    character(len=*), intent(in), optional :: note
    type(range_t) :: r
    if (.not. status%ok) return
    r = readable_range(allowed, name, status)
    if (status%ok) call need_real(in_range(r, value), file, group, name, value, with_note(allowed, note), status)
  end subroutine need_range_real

  subroutine need_range_integer(allowed, file, group, name, value, status, note)
    character(len=*), intent(in) :: allowed, file, group, name
    integer, intent(in) :: value
    type(status_t), intent(inout) :: status
    character(len=*), intent(in), optional :: note
    type(range_t) :: r
    if (.not. status%ok) return
    r = readable_range(allowed, name, status)
    if (status%ok) call need_integer(in_range(r, real(value, dp)), file, group, name, value, with_note(allowed, note), &
                                    status)
  end subroutine need_range_integer

  !> The range `text` of variable `name` (without its index); a text that cannot be read
  !> fails `status` (a fault of the program).
  function readable_range(text, name, status) result(r)
    character(len=*), intent(in) :: text, name
    type(status_t), intent(inout) :: status
    type(range_t) :: r
    integer :: open_at
    open_at = index(name, '(')
    if (open_at == 0) open_at = len(name) + 1
    r = range_of(text, name(:open_at - 1))
    if (.not. r%valid) call fail(status, 'the range "'//text//'" of '//name//' cannot be read (a fault of the program)')
  end function readable_range

  pure function with_note(allowed, note) result(text)
    character(len=*), intent(in) :: allowed
    character(len=*), intent(in), optional :: note
    character(len=:), allocatable :: text
    text = allowed
    if (present(note)) text = allowed//note
  end function with_note

  pure function outside(file, group, name, value, allowed) result(text)
    character(len=*), intent(in) :: file, group, name, value, allowed
    character(len=:), allocatable :: text
    text = file//': &'//group//' '//name//' = '//value//' is outside the allowed range '//allowed
  end function outside

end module voussoir_input_range
