!> tests/namelist/layouts.nml, every namelist layout gfortran's own READ accepts (several
!> groups on a line, a group over many lines, `!` comments, `&end` and `$end`, repeated
!> commas in a list, strings with slashes, quotes and `!`), read by the project's reader
!> (the group check and the tables of the drivers) and by gfortran's NAMELIST READ: every
!> group is found, and every value is the same to the bit (issue 34: a group after the
!> first on a line was ignored).
!>     test_namelist_layouts PATH/layouts.nml
program test_namelist_layouts
  use, intrinsic :: iso_fortran_env, only: int64
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t
  use voussoir_text, only: lower
  use voussoir_namelist_check, only: check_groups
  use voussoir_namelist_group, only: nml_group_t
  use voussoir_config, only: config_t, config_groups
  use voussoir_wall_config, only: wall_group
  use voussoir_load_config, only: load_group
  use voussoir_assert, only: assert_true, assert_summary
  implicit none

  character(len=1024) :: path
  type(config_t), target :: cfg
  type(config_t) :: defaults
  type(nml_group_t) :: tables(6)
  type(status_t) :: status
  logical :: found
  integer :: k, unit, ios
  character(len=512) :: iomsg

  ! gfortran's side: variables of the same names, starting from the same defaults.
  real(dp) :: embrace_deg, joint_friction(0:255), dt_s, theta, frequency_hz, amplitude_m, lead_s, rest_s
  real(dp) :: dead_load_n_per_m, dead_load_x0_m, hinge_gap_m
  integer :: n_voussoirs, courses, blocks_per_course, n_attack, n_full, every
  character(len=16) :: waveform
  character(len=512) :: record_file, file
  namelist /arch/ embrace_deg, n_voussoirs, joint_friction
  namelist /solver/ dt_s, theta
  namelist /wall/ courses, blocks_per_course
  namelist /motion/ waveform, frequency_hz, amplitude_m, lead_s, rest_s, record_file, n_attack, n_full
  namelist /load/ dead_load_n_per_m, dead_load_x0_m
  namelist /output/ file, every, hinge_gap_m

  call get_command_argument(1, path)
  call assert_true(len_trim(path) > 0, 'usage: test_namelist_layouts PATH/layouts.nml')

  ! The project's reader, as read_config and the drivers run it.
  call check_groups(trim(path), [character(len=8) :: 'arch', 'motion', 'solver', 'output', 'wall', 'load'], status)
  call assert_true(status%ok, 'the groups are checked: '//trim(status%message))
  call config_groups(cfg, tables(1:4))
  call wall_group(cfg%wall, tables(5))
  call load_group(cfg%load, tables(6))
  do k = 1, size(tables)
    call tables(k)%read(trim(path), status, found=found)
    call assert_true(status%ok .and. found, '&'//trim(tables(k)%name)//' is found and read: '//trim(status%message))
  end do

  ! gfortran's NAMELIST READ of the same file, each group from the file's start.
  embrace_deg = defaults%arch%embrace_deg; n_voussoirs = defaults%arch%n_voussoirs
  joint_friction = defaults%arch%joint_friction
  dt_s = defaults%solver%dt_s; theta = defaults%solver%theta
  courses = defaults%wall%courses; blocks_per_course = defaults%wall%blocks_per_course
  waveform = defaults%motion%waveform; frequency_hz = defaults%motion%frequency_hz
  amplitude_m = defaults%motion%amplitude_m; lead_s = defaults%motion%lead_s; rest_s = defaults%motion%rest_s
  record_file = defaults%motion%record_file; n_attack = defaults%motion%n_attack; n_full = defaults%motion%n_full
  dead_load_n_per_m = defaults%load%dead_load_n_per_m; dead_load_x0_m = defaults%load%dead_load_x0_m
  file = defaults%output%file; every = defaults%output%every; hinge_gap_m = defaults%output%hinge_gap_m
  open (newunit=unit, file=trim(path), status='old', action='read')
  read (unit, nml=arch, iostat=ios, iomsg=iomsg)
  call assert_true(ios == 0, 'gfortran reads &arch: '//trim(iomsg))
  rewind (unit)
  read (unit, nml=solver, iostat=ios, iomsg=iomsg)
  call assert_true(ios == 0, 'gfortran reads &solver: '//trim(iomsg))
  rewind (unit)
  read (unit, nml=wall, iostat=ios, iomsg=iomsg)
  call assert_true(ios == 0, 'gfortran reads &wall: '//trim(iomsg))
  rewind (unit)
  read (unit, nml=motion, iostat=ios, iomsg=iomsg)
  call assert_true(ios == 0, 'gfortran reads &motion: '//trim(iomsg))
  rewind (unit)
  read (unit, nml=load, iostat=ios, iomsg=iomsg)
  call assert_true(ios == 0, 'gfortran reads $load: '//trim(iomsg))
  rewind (unit)
  read (unit, nml=output, iostat=ios, iomsg=iomsg)
  call assert_true(ios == 0, 'gfortran reads &output: '//trim(iomsg))
  close (unit)

  ! The same bits, and each value read (unlike its default: no group skipped by both).
  call same('embrace_deg', cfg%arch%embrace_deg, embrace_deg, defaults%arch%embrace_deg)
  call assert_true(cfg%arch%n_voussoirs == n_voussoirs .and. n_voussoirs == 11, 'n_voussoirs')
  do k = 0, ubound(joint_friction, 1)
    call assert_true(bits(cfg%arch%joint_friction(k)) == bits(joint_friction(k)), 'joint_friction, every entry')
  end do
  call assert_true(joint_friction(0) == 0.4_dp .and. joint_friction(1) == defaults%arch%joint_friction(1) .and. &
                   joint_friction(2) == 0.45_dp .and. joint_friction(4) == defaults%arch%joint_friction(4) .and. &
                   joint_friction(5) == 0.5_dp .and. joint_friction(7) == 0.35_dp, &
                   'joint_friction: repeated commas keep the entries they skip')
  call same('dt_s (2nd group of line 4)', cfg%solver%dt_s, dt_s, defaults%solver%dt_s)
  call same('theta (ended by / without a blank)', cfg%solver%theta, theta, defaults%solver%theta)
  call assert_true(cfg%wall%blocks_per_course == blocks_per_course .and. blocks_per_course == 3 .and. &
                   cfg%wall%courses == courses, 'blocks_per_course (3rd group of line 4)')
  call assert_true(cfg%motion%waveform == lower(waveform) .and. cfg%motion%waveform == 'afd' .and. waveform == 'AFD', &
                   'waveform: a choice in any case, kept in lower case')
  call same('frequency_hz (its value on the next line)', cfg%motion%frequency_hz, frequency_hz, &
            defaults%motion%frequency_hz)
  call same('amplitude_m', cfg%motion%amplitude_m, amplitude_m, defaults%motion%amplitude_m)
  call same('lead_s', cfg%motion%lead_s, lead_s, defaults%motion%lead_s)
  call same('rest_s (after a semicolon and a tab)', cfg%motion%rest_s, rest_s, defaults%motion%rest_s)
  call assert_true(cfg%motion%record_file == record_file .and. record_file == 'records/x/y.csv', &
                   'record_file: a string with slashes in double quotes')
  call assert_true(cfg%motion%n_attack == n_attack .and. n_attack == 2 .and. cfg%motion%n_full == n_full .and. &
                   n_full == 3, 'n_attack, n_full: blanks between assignments; &end')
  call same('dead_load_n_per_m ($load ... $end)', cfg%load%dead_load_n_per_m, dead_load_n_per_m, &
            defaults%load%dead_load_n_per_m)
  call same('dead_load_x0_m', cfg%load%dead_load_x0_m, dead_load_x0_m, defaults%load%dead_load_x0_m)
  call assert_true(cfg%output%file == file .and. file == "runs/it's a/b ! no comment.h5", &
                   "file (after $end on its line): slashes, a doubled quote and '!' in a string")
  call assert_true(cfg%output%every == every .and. every == 7, 'every (a group over two lines)')
  call same('hinge_gap_m (before &end and a comment)', cfg%output%hinge_gap_m, hinge_gap_m, defaults%output%hinge_gap_m)
  call assert_summary()

contains

  pure integer(int64) function bits(x)
    real(dp), intent(in) :: x
    bits = transfer(x, 0_int64)
  end function bits

  subroutine same(name, mine, gfortran, default)
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: mine, gfortran, default
    call assert_true(bits(mine) == bits(gfortran) .and. gfortran /= default, &
                     name//': the bits of gfortran''s read, and not the default')
  end subroutine same

end program test_namelist_layouts
