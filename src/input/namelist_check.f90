!> The groups of an input file: a group the driver does not know, or one written twice,
!> is refused (`check_groups`: every driver, every input), wherever it stands on a line.
!> What is inside a group is voussoir_namelist_group's.
module voussoir_namelist_check
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa
  use voussoir_namelist_text, only: nml_group_place_t, list_groups
  implicit none
  private

  public :: check_groups

contains

  !> Fail if `path` has a namelist group not in `allowed` (names without '&'), or one
  !> twice, or cannot be read as namelist groups (voussoir_namelist_text).
  subroutine check_groups(path, allowed, status)
    character(len=*), intent(in) :: path
    character(len=*), intent(in) :: allowed(:)
    type(status_t), intent(inout) :: status
    type(nml_group_place_t), allocatable :: places(:)
    integer :: first_line(size(allowed))
    character(len=:), allocatable :: list
    integer :: k, j

    call list_groups(path, places, status)
    if (.not. status%ok) return
    list = ''
    do k = 1, size(allowed)
      list = list//' &'//trim(allowed(k))
    end do
    first_line = 0
    do j = 1, size(places)
      associate (name => places(j)%name, line => places(j)%line)
        ! findloc would compare texts of different lengths without the blank padding of ==.
        k = 0
        do while (k < size(allowed))
          k = k + 1
          if (allowed(k) == name) exit
        end do
        if (allowed(k) /= name) then
          call fail(status, path//':'//itoa(line)//': unknown namelist group &'//name//' (allowed:'//list//')')
          return
        end if
        ! A second group of the same name would be silently ignored by the read.
        if (first_line(k) > 0) then
          call fail(status, path//':'//itoa(line)//': namelist group &'//name//' appears a second time (first at '// &
                    'line '//itoa(first_line(k))//'): write each group once')
          return
        end if
        first_line(k) = line
      end associate
    end do
  end subroutine check_groups

end module voussoir_namelist_check
