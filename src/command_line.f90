!> The command line of the drivers: one input file, `--help` and `--version` (used by the
!> programs in drivers/ only; the kernel itself prints nothing).
module voussoir_command_line
  use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
  use voussoir_version, only: code_version
  implicit none
  private
  public :: input_argument

contains

  !> The input file named on the command line, and which of the driver's own `flags`
  !> were given. `--help` prints `usage` and `about` and stops (exit 0); `--version`
  !> prints the code version and stops (exit 0); anything but one file name and those
  !> flags prints the usage on standard error and stops (exit 2).
  subroutine input_argument(program, usage, about, path, flags, given)
    character(len=*), intent(in) :: program, usage, about
    character(len=*), intent(out) :: path
    character(len=*), intent(in), optional :: flags(:)
    logical, intent(out), optional :: given(:)
    character(len=1024) :: arg
    integer :: k, j
    logical :: bad

    path = ''
    bad = .false.
    if (present(given)) given = .false.
    do k = 1, command_argument_count()
      call get_command_argument(k, arg)
      select case (trim(arg))
      case ('--help', '-h')
        write (output_unit, '(a)') 'usage: '//usage, '', about
        stop 0, quiet=.true.
      case ('--version')
        write (output_unit, '(a)') program//' ('//code_version//')'
        stop 0, quiet=.true.
      end select
      j = 0
      if (present(flags)) j = findloc(flags, trim(arg), dim=1)
      if (j > 0 .and. present(given)) then
        given(j) = .true.
      else if (arg(1:1) == '-' .or. len_trim(path) > 0) then
        bad = .true.
      else
        path = arg
      end if
    end do
    if (bad .or. len_trim(path) == 0) then
      write (error_unit, '(a)') 'usage: '//usage//'   (--help for more)'
      stop 2, quiet=.true.
    end if
  end subroutine input_argument

end module voussoir_command_line
