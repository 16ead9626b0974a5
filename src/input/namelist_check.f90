!> The groups of an input file: a group the driver does not know, or one written twice,
!> is refused (`check_groups`: every driver, every input). What is inside a group is
!> voussoir_namelist_group's.
module voussoir_namelist_check
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: lower
  use voussoir_line_reader, only: read_line
  implicit none
  private

  public :: check_groups

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

end module voussoir_namelist_check
