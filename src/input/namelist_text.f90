!> The text of one namelist group, split as gfortran's namelist read splits it: each
!> `name = values` or `name(k) = value`, its values as written (a repeat count `r*`
!> kept apart, a null value marked), for voussoir_namelist_group to convert.
!>
!> The whole file is read as a sequence of groups, wherever they stand on a line: `&group`
!> (or `$group`) opens one, `/`, `&end` or `$end` closes it, and the next may follow on
!> the same line (`&arch friction = 0.3 / &motion waveform = 'afd' /`), as gfortran's
!> namelist read finds each group; the end of the file closes the last group. Inside a
!> group: values separated by commas, semicolons or blanks over any number of lines; `!`
!> comments; strings in ' or " (a doubled quote stands for one); `r*value` and `r*`.
!> Never silently skipped: text outside every group (where gfortran skips, and a group
!> written without its `&` would be lost) and a folder or unreadable file given as the
!> input are refused, naming the file and line.
!> What the project's own rules refuse here, gfortran refuses as well (an unquoted text,
!> an element with more than one value), but with a message naming the variable.
module voussoir_namelist_text
  use, intrinsic :: iso_fortran_env, only: iostat_end
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: lower, itoa
  use voussoir_line_reader, only: read_line
  implicit none
  private

  public :: nml_value_t, nml_assignment_t, nml_group_place_t, read_group_text, list_groups

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

  !> A group of the file: its name (lower case, without '&') and the line it opens on.
  type :: nml_group_place_t
    character(len=:), allocatable :: name
    integer :: line = 0
  end type nml_group_place_t

  integer, parameter :: word = 1, equals = 2, comma = 3

  !> A piece of the group's text: a word (a name or a value, quoted strings included),
  !> '=' or a separating comma.
  type :: token_t
    integer :: kind = word
    character(len=:), allocatable :: text
    integer :: line = 0
  end type token_t

  !> Blanks: space, tab and the carriage return of a file written on Windows.
  character(len=*), parameter :: blanks = ' '//achar(9)//achar(13)
  !> What may follow a group's name: a blank, a separator, its end or a comment.
  character(len=*), parameter :: after_name = blanks//',;/!'
  character(len=*), parameter :: name_characters = &
    'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_'

contains

  !> The assignments of group `group` in `path`; found = .false. (and no assignment)
  !> when the file has no such group (the first of that name when it has several:
  !> voussoir_namelist_check refuses a second). A malformed file fails `status` with its line.
  subroutine read_group_text(path, group, found, assignments, status)
    character(len=*), intent(in) :: path, group
    logical, intent(out) :: found
    type(nml_assignment_t), allocatable, intent(out) :: assignments(:)
    type(status_t), intent(inout) :: status
    type(token_t), allocatable :: tokens(:)
    type(nml_group_place_t), allocatable :: places(:)

    allocate (assignments(0))
    call scan_groups(path, lower(group), found, tokens, places, status)
    if (.not. (found .and. status%ok)) then
      found = found .and. status%ok
      return
    end if
    call split_assignments(path, group, tokens, assignments, status)
  end subroutine read_group_text

  !> Every group of `path` in the order written, with the line each opens on; a
  !> malformed file fails `status` with its line.
  subroutine list_groups(path, places, status)
    character(len=*), intent(in) :: path
    type(nml_group_place_t), allocatable, intent(out) :: places(:)
    type(status_t), intent(inout) :: status
    type(token_t), allocatable :: tokens(:)
    logical :: found
    call scan_groups(path, '', found, tokens, places, status)
  end subroutine list_groups

  !> Read the whole of `path` as namelist groups: `places` lists them all, and `tokens`
  !> holds the text of the first group named `wanted` (lower case; '' for none).
  subroutine scan_groups(path, wanted, found, tokens, places, status)
    character(len=*), intent(in) :: path, wanted
    logical, intent(out) :: found
    type(token_t), allocatable, intent(out) :: tokens(:)
    type(nml_group_place_t), allocatable, intent(out) :: places(:)
    type(status_t), intent(inout) :: status
    type(token_t), allocatable :: discarded(:)
    character(len=:), allocatable :: line, group
    character(len=512) :: iomsg
    integer :: unit, ios, line_no, i, next
    logical :: inside, ended, folder, collect

    found = .false.
    allocate (tokens(0), places(0), discarded(0))
    ! gfortran opens a folder and reads it as an empty file: it would run on defaults.
    inquire (file=path//'/.', exist=folder)
    if (folder) then
      call fail(status, path//': is a folder, not an input file: name a namelist file (e.g. input/seed_156.nml)')
      return
    end if
    open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      call fail(status, path//': cannot open input: '//trim(iomsg))
      return
    end if
    line_no = 0
    inside = .false.
    collect = .false.
    group = ''
    do
      iomsg = ''
      call read_line(unit, line, ios, iomsg)
      if (ios == iostat_end) exit
      if (ios /= 0) then
        call fail(status, path//':'//itoa(line_no + 1)//': cannot read input: '//trim(iomsg))
        exit
      end if
      line_no = line_no + 1
      i = 1
      do while (i <= len(line) .and. status%ok)
        if (inside) then
          ended = .false.
          if (collect) then
            call line_tokens(path, group, line, i, line_no, tokens, ended, next, status)
          else
            call line_tokens(path, group, line, i, line_no, discarded, ended, next, status)
            deallocate (discarded)
            allocate (discarded(0))
          end if
          i = next
          if (ended) then
            inside = .false.
            if (collect) found = .true.
            collect = .false.
          end if
        else
          call group_opening(path, line, line_no, i, group, status)
          if (.not. status%ok .or. len(group) == 0) exit   ! a comment, or the end of the line
          if (group == 'end') cycle                         ! a stray &end closes nothing: nothing lost
          places = [places, nml_group_place_t(group, line_no)]
          inside = .true.
          collect = group == wanted .and. len(wanted) > 0 .and. .not. found
        end if
      end do
      if (.not. status%ok) exit
    end do
    close (unit)
    ! The end of the file ends the last group (gfortran reads its values, then reports
    ! the end of the file).
    if (status%ok .and. collect) found = .true.
    if (.not. status%ok) found = .false.
  end subroutine scan_groups

  !> Outside every group, from line(i:): skip blanks; at `&name` (or `$name`) return its
  !> name in lower case and move i past it; at a comment or the end of the line return
  !> '' with i past the line. Any other text is refused: gfortran would skip it, and with
  !> it a group written without its '&' or after a '/' left in an unquoted text.
  subroutine group_opening(path, line, line_no, i, group, status)
    character(len=*), intent(in) :: path, line
    integer, intent(in) :: line_no
    integer, intent(inout) :: i
    character(len=:), allocatable, intent(out) :: group
    type(status_t), intent(inout) :: status
    integer :: first, after
    character(len=:), allocatable :: stray

    group = ''
    first = verify(line(i:), blanks)
    if (first == 0) then
      i = len(line) + 1
      return
    end if
    i = i + first - 1
    if (line(i:i) == '!') then
      i = len(line) + 1
      return
    end if
    if (line(i:i) == '&' .or. line(i:i) == '$') then
      after = verify(line(i + 1:), name_characters)
      if (after == 0) then
        after = len(line) + 1
      else
        after = i + after
      end if
      group = lower(line(i + 1:after - 1))
      if (len(group) > 0) then
        if (after > len(line)) then
          i = after
          return
        else if (scan(line(after:after), after_name) > 0) then
          i = after
          return
        end if
      end if
      group = ''
      stray = line(i:)
      call fail(status, path//':'//itoa(line_no)//": '"//short(stray)//"' is not the start of a namelist "// &
                'group: write &name followed by a blank (e.g. &arch friction = 0.5 /)')
      return
    end if
    stray = line(i:)
    call fail(status, path//':'//itoa(line_no)//": '"//short(stray)//"' stands outside every namelist group "// &
              "(a group begins with &name and ends with /, a comment with !; a text with '/' in it goes in quotes)")
  end subroutine group_opening

  !> At most 40 characters of `text`, trimmed.
  pure function short(text) result(s)
    character(len=*), intent(in) :: text
    character(len=:), allocatable :: s
    s = trim(text)
    if (len(s) > 40) s = s(:37)//'...'
  end function short

  !> Append the tokens of line(from:) inside group `group`; ended when its '/' or &end
  !> is reached, and `next` is where the text after it starts (past the line when the
  !> group goes on).
  subroutine line_tokens(path, group, line, from, line_no, tokens, ended, next, status)
    character(len=*), intent(in) :: path, group, line
    integer, intent(in) :: from, line_no
    type(token_t), allocatable, intent(inout) :: tokens(:)
    logical, intent(inout) :: ended
    integer, intent(out) :: next
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: current
    integer :: i, close_at

    current = ''
    i = from
    next = len(line) + 1
    do while (i <= len(line))
      select case (line(i:i))
      case (' ', achar(9), achar(13))
        call end_word()
      case (',', ';')
        call end_word()
        if (.not. ended) tokens = [tokens, token_t(comma, ',', line_no)]
      case ('=')
        call end_word()
        if (.not. ended) tokens = [tokens, token_t(equals, '=', line_no)]
      case ('/')
        call end_word()
        if (.not. ended) then
          ended = .true.
          i = i + 1
        end if
      case ('!')
        call end_word()
        if (.not. ended) i = len(line) + 1
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
      if (.not. status%ok) return
      if (ended) then
        next = i
        return
      end if
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
