!> The text of one namelist group, split as gfortran's namelist read splits it: each
!> `name = values` or `name(k) = value`, its values as written (a repeat count `r*`
!> kept apart, a null value marked), for voussoir_namelist_group to convert.
!>
!> Accepted: `&group` (or `$group`) at the start of a line, ended by `/`, `&end`,
!> `$end` or the end of the file; values separated by commas, semicolons or blanks over any number of lines;
!> `!` comments; strings in ' or " (a doubled quote stands for one); `r*value` and `r*`.
!> What the project's own rules refuse here, gfortran refuses as well (an unquoted text,
!> an element with more than one value), but with a message naming the variable.
module voussoir_namelist_text
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: lower, itoa
  use voussoir_line_reader, only: read_line
  implicit none
  private

  public :: nml_value_t, nml_assignment_t, read_group_text

  !> One value as written, or a null value (`,,` or `r*`): the entry keeps what it held.
  type :: nml_value_t
    character(len=:), allocatable :: text  !! without the repeat count; '' when null
    integer :: repeat = 1                  !! r of `r*value`
    logical :: null = .false.
  end type nml_value_t

  !> One `name = values` of the group.
  type :: nml_assignment_t
    character(len=:), allocatable :: name     !! lower case, without the index
    character(len=:), allocatable :: written  !! as written, index included
    logical :: indexed = .false.              !! `name(k) =`: one entry of a list
    integer :: index = 0
    integer :: line = 0                       !! line of the name in the file
    type(nml_value_t), allocatable :: values(:)
  end type nml_assignment_t

  integer, parameter :: word = 1, equals = 2, comma = 3

  !> A piece of the group's text: a word (a name or a value, quoted strings included),
  !> '=' or a separating comma.
  type :: token_t
    integer :: kind = word
    character(len=:), allocatable :: text
    integer :: line = 0
  end type token_t

contains

  !> The assignments of group `group` in `path`; found = .false. (and no assignment)
  !> when the file has no such group. A malformed group fails `status` with its line.
  subroutine read_group_text(path, group, found, assignments, status)
    character(len=*), intent(in) :: path, group
    logical, intent(out) :: found
    type(nml_assignment_t), allocatable, intent(out) :: assignments(:)
    type(status_t), intent(inout) :: status
    type(token_t), allocatable :: tokens(:)

    allocate (assignments(0))
    call group_tokens(path, group, found, tokens, status)
    if (.not. (found .and. status%ok)) return
    call split_assignments(path, group, tokens, assignments, status)
  end subroutine read_group_text

  !> The tokens of group `group` in `path`, from its name to its end.
  subroutine group_tokens(path, group, found, tokens, status)
    character(len=*), intent(in) :: path, group
    logical, intent(out) :: found
    type(token_t), allocatable, intent(out) :: tokens(:)
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: line
    character(len=512) :: iomsg
    integer :: unit, ios, line_no, start
    logical :: ended

    found = .false.
    allocate (tokens(0))
    open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      call fail(status, path//': cannot open input: '//trim(iomsg))
      return
    end if
    line_no = 0
    ended = .false.
    do
      call read_line(unit, line, ios)
      if (ios /= 0) exit
      line_no = line_no + 1
      if (.not. found) then
        start = group_start(line, group)
        if (start == 0) cycle
        found = .true.
        line = line(start:)
      end if
      call line_tokens(path, group, line, line_no, tokens, ended, status)
      if (ended .or. .not. status%ok) exit
    end do
    close (unit)   ! the end of the file ends the last group, as in gfortran's read
  end subroutine group_tokens

  !> Where the text of group `group` starts in `line` (after its name), or 0 when the
  !> line does not open it.
  pure integer function group_start(line, group) result(start)
    character(len=*), intent(in) :: line, group
    integer :: first, after
    start = 0
    first = verify(line, ' '//achar(9))
    if (first == 0) return
    if (line(first:first) /= '&' .and. line(first:first) /= '$') return
    after = first + len(group) + 1
    if (len(line) < after - 1) return
    if (lower(line(first + 1:after - 1)) /= lower(group)) return
    if (len(line) >= after) then
      if (verify(line(after:after), ' ,/!'//achar(9)) /= 0) return
    end if
    start = after
  end function group_start

  !> Append the tokens of one line of the group; ended when its '/' or &end is reached.
  subroutine line_tokens(path, group, line, line_no, tokens, ended, status)
    character(len=*), intent(in) :: path, group, line
    integer, intent(in) :: line_no
    type(token_t), allocatable, intent(inout) :: tokens(:)
    logical, intent(inout) :: ended
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: current
    integer :: i, close_at

    current = ''
    i = 1
    do while (i <= len(line))
      select case (line(i:i))
      case (' ', achar(9))
        call end_word()
      case (',', ';')
        call end_word()
        tokens = [tokens, token_t(comma, ',', line_no)]
      case ('=')
        call end_word()
        tokens = [tokens, token_t(equals, '=', line_no)]
      case ('/')
        call end_word()
        ended = .true.
      case ('!')
        exit
      case ("'", '"')
        close_at = closing_quote(line, i)
        if (close_at == 0) then
          call fail(status, path//':'//itoa(line_no)//': &'//group//' '//last_name()//'the text '// &
                    trim(line(i:))//' has no closing quote ('//line(i:i)//') on its line')
          return
        end if
        current = current//line(i:close_at)
        i = close_at
      case default
        current = current//line(i:i)
      end select
      if (ended .or. .not. status%ok) return
      i = i + 1
    end do
    call end_word()

  contains

    !> The word collected so far becomes a token (&end ends the group).
    subroutine end_word()
      if (len(current) == 0) return
      if (lower(current) == '&end' .or. lower(current) == '$end') then
        ended = .true.
      else if (current(1:1) == '&' .or. current(1:1) == '$') then
        call fail(status, path//':'//itoa(line_no)//': group '//current//' begins before &'//group// &
                  " is closed: end &"//group//' with /')
      else
        tokens = [tokens, token_t(word, current, line_no)]
      end if
      current = ''
    end subroutine end_word

    !> 'name: ' of the variable being assigned, for the message of an open string.
    function last_name() result(text)
      character(len=:), allocatable :: text
      integer :: n
      text = ''
      n = size(tokens)
      if (len(current) > 0 .or. n < 2) return
      if (tokens(n)%kind == equals .and. tokens(n - 1)%kind == word) text = tokens(n - 1)%text//': '
    end function last_name

  end subroutine line_tokens

  !> The position of the quote closing the string that opens at line(open_at:open_at),
  !> 0 when the line ends first (a doubled quote is part of the string).
  pure integer function closing_quote(line, open_at) result(k)
    character(len=*), intent(in) :: line
    integer, intent(in) :: open_at
    k = open_at + 1
    do while (k <= len(line))
      if (line(k:k) == line(open_at:open_at)) then
        if (k == len(line)) return
        if (line(k + 1:k + 1) /= line(open_at:open_at)) return
        k = k + 1
      end if
      k = k + 1
    end do
    k = 0
  end function closing_quote

  !> Group the tokens into assignments: a word followed by '=' names a variable, and
  !> the words up to the next such name are its values.
  subroutine split_assignments(path, group, tokens, assignments, status)
    character(len=*), intent(in) :: path, group
    type(token_t), intent(in) :: tokens(:)
    type(nml_assignment_t), allocatable, intent(inout) :: assignments(:)
    type(status_t), intent(inout) :: status
    type(nml_assignment_t) :: a
    integer :: k
    logical :: after_value

    k = 1
    do while (k <= size(tokens))
      if (tokens(k)%kind == comma) then
        k = k + 1
        cycle
      end if
      if (.not. names_variable(tokens, k)) then
        call fail(status, path//':'//itoa(tokens(k)%line)//': &'//group//' '//tokens(k)%text// &
                  " is not followed by '=' (write name = value)")
        return
      end if
      call name_and_index(path, group, tokens(k), a, status)
      if (.not. status%ok) return
      allocate (a%values(0))
      k = k + 2
      after_value = .false.
      do while (k <= size(tokens))
        if (names_variable(tokens, k)) exit
        if (tokens(k)%kind == equals) then
          call fail(status, path//':'//itoa(tokens(k)%line)//': &'//group//' '//a%written// &
                    " has a second '=' (write name = value)")
          return
        end if
        if (tokens(k)%kind == comma) then
          ! A comma right after a value only separates; any other comma is a null value.
          if (.not. after_value) a%values = [a%values, nml_value_t('', 1, .true.)]
          after_value = .false.
        else
          a%values = [a%values, value_of(tokens(k)%text)]
          after_value = .true.
        end if
        k = k + 1
      end do
      assignments = [assignments, a]
      deallocate (a%values)
    end do
  end subroutine split_assignments

  !> Whether tokens(k) is a word followed by '='.
  pure logical function names_variable(tokens, k)
    type(token_t), intent(in) :: tokens(:)
    integer, intent(in) :: k
    names_variable = .false.
    if (k >= size(tokens)) return
    names_variable = tokens(k)%kind == word .and. tokens(k + 1)%kind == equals
  end function names_variable

  !> The name of `name` or `name(k)`, and k.
  subroutine name_and_index(path, group, token, a, status)
    character(len=*), intent(in) :: path, group
    type(token_t), intent(in) :: token
    type(nml_assignment_t), intent(inout) :: a
    type(status_t), intent(inout) :: status
    integer :: open_at, ios

    a%written = token%text
    a%line = token%line
    a%indexed = .false.
    a%index = 0
    open_at = index(token%text, '(')
    if (open_at == 0) then
      a%name = lower(token%text)
      return
    end if
    a%name = lower(token%text(:open_at - 1))
    a%indexed = .true.
    ios = 1
    if (token%text(len(token%text):) == ')') read (token%text(open_at + 1:len(token%text) - 1), *, iostat=ios) a%index
    if (ios /= 0) call fail(status, path//':'//itoa(token%line)//': &'//group//' '//token%text// &
                            ': the index in ( ) must be one whole number, e.g. '//a%name//'(2) = value')
  end subroutine name_and_index

  !> A value word: `r*value`, `r*` (r null values) or `value`.
  pure function value_of(text) result(v)
    character(len=*), intent(in) :: text
    type(nml_value_t) :: v
    integer :: star, ios
    v%text = text
    star = index(text, '*')
    if (star < 2) return
    if (verify(text(:star - 1), '0123456789') /= 0) return
    read (text(:star - 1), *, iostat=ios) v%repeat
    if (ios /= 0) return   ! too many digits: converted (and refused) as written
    v%text = text(star + 1:)
    v%null = len(v%text) == 0
  end function value_of

end module voussoir_namelist_text
