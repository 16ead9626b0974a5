!> What gfortran's namelist reader does not say clearly: a group the driver does not
!> know, and a variable a group does not have (the compiler's message names another
!> one). Every driver checks every group of its input with these.
module voussoir_namelist_check
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: lower, join_words
  implicit none
  private

  public :: check_groups, check_names

contains

  !> Fail if `path` has a namelist group not in `allowed` (names without '&').
  subroutine check_groups(path, allowed, status)
    character(len=*), intent(in) :: path
    character(len=*), intent(in) :: allowed(:)
    type(status_t), intent(inout) :: status
    integer :: unit, ios, line_no, k, e
    integer :: first_line(size(allowed))
    character(len=1024) :: line
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
      read (unit, '(a)', iostat=ios) line
      if (ios /= 0) exit
      line_no = line_no + 1
      line = adjustl(line)
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
    character(len=1024) :: line
    character(len=:), allocatable :: text, name
    character(len=1) :: quote
    integer :: unit, ios, i, j, k
    logical :: inside

    if (.not. status%ok) return
    open (newunit=unit, file=path, status='old', action='read', iostat=ios)
    if (ios /= 0) return   ! reported by the namelist read
    text = ''
    inside = .false.
    quote = ' '
    do
      read (unit, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (.not. inside) then
        line = adjustl(line)
        if (lower(line(1:len(group) + 1)) /= '&'//group .or. &
            verify(line(len(group) + 2:len(group) + 2), ' ,/!'//achar(9)) /= 0) cycle
        inside = .true.
        line = line(len(group) + 2:)
      end if
      ! Keep the group's text up to its closing '/', without comments and quoted text.
      do i = 1, len_trim(line)
        if (quote /= ' ') then
          if (line(i:i) == quote) quote = ' '
          cycle
        end if
        select case (line(i:i))
        case ("'", '"')
          quote = line(i:i)
          text = text//' '
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
    ! A name is the identifier before each '=' (after an optional (index)).
    do k = 1, len(text)
      if (text(k:k) /= '=') cycle
      j = k - 1
      do while (j > 0)
        if (text(j:j) /= ' ') exit
        j = j - 1
      end do
      if (j > 0) then
        if (text(j:j) == ')') then
          j = index(text(1:j), '(', back=.true.) - 1
          do while (j > 0)
            if (text(j:j) /= ' ') exit
            j = j - 1
          end do
        end if
      end if
      i = j
      do while (i > 0)
        if (verify(lower(text(i:i)), 'abcdefghijklmnopqrstuvwxyz0123456789_') /= 0) exit
        i = i - 1
      end do
      if (j <= i) cycle
      name = lower(text(i + 1:j))
      if (.not. any(known == name)) then
        call fail(status, path//': &'//group//" has no variable '"//name//"' (known: "// &
                  join_words(known)//')')
        return
      end if
    end do
  end subroutine check_names

end module voussoir_namelist_check
