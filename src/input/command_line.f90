!> The command line of the drivers: one input file, `--help` and `--version` (used by the
!> programs in drivers/ only; the kernel itself prints nothing). It never stops: it says
!> with which exit code the program should stop, and the program alone stops.
module voussoir_command_line
  use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
  use voussoir_version, only: code_version
  use voussoir_namelist_group, only: nml_group_t
  use voussoir_namelist_help, only: groups_help
  implicit none
  private
  public :: input_argument, write_warnings

contains

  !> The input file named on the command line, and which of the driver's own `flags`
  !> were given. `exit_code` is -1 when the program should go on; else the program stops
  !> with it: `--help` prints `usage`, `about` and the variables of the namelist
  !> `groups` the driver reads (their tables, built over a default configuration) (0);
  !> `--version` prints the code version (0); anything but one file name and those flags prints the usage on
  !> standard error (2), after naming the first unknown option or extra argument.
  subroutine input_argument(program, usage, about, path, exit_code, flags, given, groups)
    character(len=*), intent(in) :: program, usage, about
    character(len=*), intent(out) :: path
    integer, intent(out) :: exit_code
    character(len=*), intent(in), optional :: flags(:)
    logical, intent(out), optional :: given(:)
    type(nml_group_t), intent(in), optional :: groups(:)
    character(len=1024) :: arg
    character(len=:), allocatable :: why
    integer :: k, j
    logical :: bad

    path = ''
    exit_code = -1
    bad = .false.
    why = ''
    if (present(given)) given = .false.
    do k = 1, command_argument_count()
      call get_command_argument(k, arg)
      select case (trim(arg))
      case ('--help', '-h')
        write (output_unit, '(a)') 'usage: '//usage, '', about
        if (present(groups)) write (output_unit, '(a)') '', groups_help(groups)
        exit_code = 0
        return
      case ('--version')
        write (output_unit, '(a)') program//' ('//code_version//')'
        exit_code = 0
        return
      end select
      j = 0
      if (present(flags)) j = findloc(flags, trim(arg), dim=1)
      if (j > 0 .and. present(given)) then
        given(j) = .true.
      else if (arg(1:1) == '-') then
        if (.not. bad) why = program//": unknown option '"//trim(arg)//"'"
        bad = .true.
      else if (len_trim(path) > 0) then
        if (.not. bad) why = program//": one input file only: '"//trim(arg)//"' is a second one"
        bad = .true.
      else
        path = arg
      end if
    end do
    if (bad .or. len_trim(path) == 0) then
      if (len_trim(path) == 0 .and. .not. bad) why = program//': no input file named'
      write (error_unit, '(a)') why
      write (error_unit, '(a)') 'usage: '//usage//'   (--help for more)'
      exit_code = 2
    end if
  end subroutine input_argument

  !> Each line of `warnings` (voussoir_config's config_t%warnings) on standard error as
  !> 'program: warning: line'; nothing when there is none.
  subroutine write_warnings(program, warnings)
    character(len=*), intent(in) :: program, warnings
    integer :: first, last
    first = 1
    do while (first <= len_trim(warnings))
      last = index(warnings(first:), new_line('a'))
      if (last == 0) then
        last = len_trim(warnings) + 1
      else
        last = first + last - 1
      end if
      write (error_unit, '(a)') program//': warning: '//warnings(first:last - 1)
      first = last + 1
    end do
  end subroutine write_warnings

end module voussoir_command_line
