!> What gfortran's namelist reader does not say clearly: a group the driver does not
!> know (`check_groups`: every driver, every input). `check_names` and
!> `check_list_lengths` serve the &sweep group's NAMELIST read until it moves onto
!> voussoir_namelist_group, whose read checks names and list lengths itself.
module voussoir_namelist_check
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: lower, join_words, itoa
  use voussoir_line_reader, only: read_line
  implicit none
  private

  public :: check_groups, check_names, check_list_lengths

contains

  !> Fail if `path` has a namelist group not in `allowed` (names without '&').
  subroutine check_groups(path, allowed, status)
    character(len=*), intent(in) :: path
    character(len=*), intent(in) :: allowed(:)
    type(status_t), intent(inout) :: status
    integer :: unit, ios, line_no, k, e
    integer :: first_line(size(allowed))
    character(len=:), allocatable :: line
    character(len=512) :: iomsg, list
    character(len=64) :: name
    character(len=16) :: num, num0

    open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      call fail(status, trim(path)//': cannot open input: '//trim(iomsg))
      return
    end if
    list = ''
    do k = 1, size(allowed)
      list = trim(list)//' &'//trim(allowed(k))
    end do
    line_no = 0
    first_line = 0
    do
      call read_line(unit, line, ios)
      if (ios /= 0) exit
      line_no = line_no + 1
      line = trim(adjustl(line))
      if (len(line) == 0) cycle
      if (line(1:1) /= '&') cycle
      e = scan(line(2:), ' ,/!'//achar(9))
      if (e == 0) then
        name = line(2:)
      else
        name = line(2:e)
      end if
      if (name == 'end' .or. len_trim(name) == 0) cycle
      if (.not. any(allowed == lower(name))) then
        write (num, '(i0)') line_no
        call fail(status, trim(path)//':'//trim(num)//': unknown namelist group &'//trim(name)// &
                  ' (allowed:'//trim(list)//')')
        exit
      end if
      ! A second group of the same name would be silently ignored by the read.
      k = findloc(allowed, lower(name), dim=1)
      if (first_line(k) > 0) then
        write (num, '(i0)') line_no
        write (num0, '(i0)') first_line(k)
        call fail(status, trim(path)//':'//trim(num)//': namelist group &'//trim(lower(name))// &
                  ' appears a second time (first at line '//trim(num0)//'): write each group once')
        exit
      end if
      first_line(k) = line_no
    end do
    close (unit)
  end subroutine check_groups

  !> Fail on a variable of namelist group `group` in `path` that is not in `known`: the
  !> compiler's own message for it names another variable.
  subroutine check_names(path, group, known, status)
    character(len=*), intent(in) :: path, group
    character(len=*), intent(in) :: known(:)
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: text, name
    integer :: k, first, last, first_entry

    if (.not. status%ok) return
    text = group_text(path, group)
    do k = 1, len(text)
      if (text(k:k) /= '=') cycle
      call name_before(text, k, first, last, first_entry)
      if (last < first) cycle
      name = lower(text(first:last))
      if (.not. any(known == name)) then
        call fail(status, path//': &'//group//" has no variable '"//name//"' (known: "// &
                  join_words(known)//')')
        return
      end if
    end do
  end subroutine check_names

  !> Fail if list `names(m)` of group `group` in `path` is given more than
  !> `max_values(m)` values (the compiler's message for it names the first value too
  !> many as an unknown variable). Counts `r*value` as r values, and `name(k) = ...`
  !> from entry k.
  subroutine check_list_lengths(path, group, names, max_values, status)
    character(len=*), intent(in) :: path, group
    character(len=*), intent(in) :: names(:)
    integer, intent(in) :: max_values(:)
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: text
    integer :: k, first, last, first_entry, list, list_first_entry, values_from, values_to, last_entry

    if (.not. status%ok) return
    text = group_text(path, group)
    list = 0   ! the list whose values follow (0: another variable)
    list_first_entry = 1
    values_from = 1
    do k = 1, len(text) + 1
      first = len(text) + 1
      if (k <= len(text)) then
        if (text(k:k) /= '=') cycle
        call name_before(text, k, first, last, first_entry)
        if (last < first) cycle
      end if
      ! The values of the previous variable end where this name begins.
      if (list > 0) then
        values_to = first - 1
        last_entry = list_first_entry - 1 + count_values(text(values_from:values_to))
        if (last_entry > max_values(list)) then
          if (list_first_entry == 1) then
            call fail(status, path//': &'//group//' '//trim(names(list))//' has '//itoa(last_entry)// &
                      ' values; at most '//itoa(max_values(list)))
          else
            call fail(status, path//': &'//group//' '//trim(names(list))//' has values up to entry '// &
                      itoa(last_entry)//'; at most '//itoa(max_values(list)))
          end if
          return
        end if
      end if
      if (k > len(text)) exit
      list = findloc(names, lower(text(first:last)), dim=1)
      list_first_entry = first_entry
      values_from = k + 1
    end do
  end subroutine check_list_lengths

  !> The text of group `group` in `path` up to its closing '/', without comments, each
  !> quoted string as one 'q' (a value, never taken for a name); '' if absent.
  function group_text(path, group) result(text)
    character(len=*), intent(in) :: path, group
    character(len=:), allocatable :: text
    character(len=:), allocatable :: line
    character(len=1) :: quote
    integer :: unit, ios, i
    logical :: inside

    text = ''
    open (newunit=unit, file=path, status='old', action='read', iostat=ios)
    if (ios /= 0) return   ! reported by the namelist read
    inside = .false.
    quote = ' '
    do
      call read_line(unit, line, ios)
      if (ios /= 0) exit
      if (.not. inside) then
        line = trim(adjustl(line))
        if (len(line) < len(group) + 1) cycle
        if (lower(line(1:len(group) + 1)) /= '&'//group) cycle
        if (len(line) > len(group) + 1) then
          if (verify(line(len(group) + 2:len(group) + 2), ' ,/!'//achar(9)) /= 0) cycle
        end if
        inside = .true.
        line = line(len(group) + 2:)
      end if
      do i = 1, len_trim(line)
        if (quote /= ' ') then
          if (line(i:i) == quote) quote = ' '
          cycle
        end if
        select case (line(i:i))
        case ("'", '"')
          quote = line(i:i)
          text = text//'q'
        case ('!')
          exit
        case ('/')
          inside = .false.
          exit
        case default
          text = text//line(i:i)
        end select
      end do
      if (.not. inside .and. len(text) > 0) exit
      text = text//' '
    end do
    close (unit)
  end function group_text

  !> The name text(first:last) assigned by the '=' at text(k:k) (last < first if none),
  !> and the entry its values start at: k of `name(k) =`, else 1.
  pure subroutine name_before(text, k, first, last, first_entry)
    character(len=*), intent(in) :: text
    integer, intent(in) :: k
    integer, intent(out) :: first, last, first_entry
    integer :: j, open_at, ios

    first_entry = 1
    j = k - 1
    do while (j > 0)
      if (text(j:j) /= ' ') exit
      j = j - 1
    end do
    if (j > 0) then
      if (text(j:j) == ')') then
        open_at = index(text(1:j), '(', back=.true.)
        if (open_at > 0) then
          read (text(open_at + 1:j - 1), *, iostat=ios) first_entry
          if (ios /= 0) first_entry = 1
        end if
        j = open_at - 1
        do while (j > 0)
          if (text(j:j) /= ' ') exit
          j = j - 1
        end do
      end if
    end if
    last = j
    first = j + 1
    do while (first > 1)
      if (verify(lower(text(first - 1:first - 1)), 'abcdefghijklmnopqrstuvwxyz0123456789_') /= 0) exit
      first = first - 1
    end do
  end subroutine name_before

  !> How many values a namelist value list holds (`r*value` and `r*` count r).
  pure integer function count_values(values) result(n)
    character(len=*), intent(in) :: values
    integer :: i, start, star, repeat, ios
    character(len=*), parameter :: separators = ' ,'//achar(9)

    n = 0
    i = 1
    do while (i <= len(values))
      if (index(separators, values(i:i)) > 0) then
        i = i + 1
        cycle
      end if
      start = i
      do while (i <= len(values))
        if (index(separators, values(i:i)) > 0) exit
        i = i + 1
      end do
      if (values(start:start) == '&') cycle   ! an '&end' closing the group
      repeat = 1
      star = index(values(start:i - 1), '*')
      if (star > 1) then
        read (values(start:start + star - 2), *, iostat=ios) repeat
        if (ios /= 0 .or. repeat < 1) repeat = 1
      end if
      n = n + repeat
    end do
  end function count_values

end module voussoir_namelist_check
