!> The &wall group: a wall of bricks or stones laid dry instead of the arch (courses of
!> equal blocks, in running or stack bond, on one driven foundation). Input only: the
!> blocks themselves are built by voussoir_wall (src/assembly/wall.f90).
module voussoir_wall_config
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa
  use voussoir_namelist_group, only: nml_group_t
  implicit none
  private
  public :: wall_config_t, read_wall_config, wall_block_count, wall_group

  !> The bonds of a wall: running (odd courses offset by half a block, half blocks at
  !> the ends) or stack.
  character(len=*), parameter, public :: bond_running = 'running', bond_stack = 'stack'
  character(len=16), parameter :: bond_names(2) = [character(len=16) :: bond_running, bond_stack]

  integer, parameter :: max_wall_blocks = 2000000

  !> &wall: a wall instead of the arch (courses = 0: no wall).
  type :: wall_config_t
    integer :: courses = 0                    !! rows of blocks, bottom to top
    integer :: blocks_per_course = 10         !! whole blocks in a course
    real(dp) :: block_width_m = 0.20_dp       !! length of a block along the wall [m]
    real(dp) :: block_height_m = 0.10_dp      !! height of a course [m]
    character(len=16) :: bond = bond_running  !! bond_running or bond_stack
  end type wall_config_t

contains

  !> Blocks of a wall: whole blocks per course, and one more per odd course in running
  !> bond (its two half blocks).
  pure integer function wall_block_count(w)
    type(wall_config_t), intent(in) :: w
    wall_block_count = w%courses*w%blocks_per_course
    if (w%bond == bond_running) wall_block_count = wall_block_count + w%courses/2
  end function wall_block_count

  !> The &wall table over `w`.
  subroutine wall_group(w, g)
    type(wall_config_t), intent(inout), target :: w
    type(nml_group_t), intent(out) :: g
    g%name = 'wall'
    call g%add('courses', w%courses, range='1 <= courses <= 10000')
    call g%add('blocks_per_course', w%blocks_per_course, range='1 <= blocks_per_course <= 10000')
    ! At least 0.1 mm, as the blocks of a polygon file (a 1e-9 m wall "collapsed" at once).
    call g%add('block_width_m', w%block_width_m, unit='m', range='1e-4 m <= block_width_m <= 100 m')
    call g%add('block_height_m', w%block_height_m, unit='m', range='1e-4 m <= block_height_m <= 100 m')
    call g%add('bond', w%bond, choices=bond_names)
  end subroutine wall_group

  !> Read and check the &wall group of `path` (absent: no wall).
  subroutine read_wall_config(path, w, status)
    character(len=*), intent(in) :: path
    type(wall_config_t), intent(out), target :: w
    type(status_t), intent(inout) :: status
    type(nml_group_t) :: g

    if (.not. status%ok) return
    call wall_group(w, g)
    call g%read(path, status)
    if (.not. status%ok .or. w%courses == 0) return
    call g%check(path, status)
    if (status%ok .and. wall_block_count(w) > max_wall_blocks) &
      call fail(status, trim(path)//': &wall of '//itoa(w%courses)//' courses x '//itoa(w%blocks_per_course)// &
                ' blocks has more than '//itoa(max_wall_blocks)//' blocks')
  end subroutine read_wall_config

end module voussoir_wall_config
