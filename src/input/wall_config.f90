!> The &wall group: a wall of bricks or stones laid dry instead of the arch (courses of
!> equal blocks, in running or stack bond, on one driven foundation). Input only: the
!> blocks themselves are built by voussoir_wall (src/assembly/wall.f90).
module voussoir_wall_config
  use, intrinsic :: iso_fortran_env, only: iostat_end
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa, fmt_real, lower
  use voussoir_namelist_check, only: check_names
  implicit none
  private
  public :: wall_config_t, read_wall_config, wall_block_count

  integer, parameter :: max_wall_blocks = 2000000

  !> &wall: a wall instead of the arch (courses = 0: no wall).
  type :: wall_config_t
    integer :: courses = 0                    !! rows of blocks, bottom to top
    integer :: blocks_per_course = 10         !! whole blocks in a course
    real(dp) :: block_width_m = 0.20_dp       !! length of a block along the wall [m]
    real(dp) :: block_height_m = 0.10_dp      !! height of a course [m]
    character(len=16) :: bond = 'running'     !! 'running' (odd courses offset by half a block, half blocks at the ends) or 'stack'
  end type wall_config_t

contains

  !> Blocks of a wall: whole blocks per course, and one more per odd course in running
  !> bond (its two half blocks).
  pure integer function wall_block_count(w)
    type(wall_config_t), intent(in) :: w
    wall_block_count = w%courses*w%blocks_per_course
    if (w%bond == 'running') wall_block_count = wall_block_count + w%courses/2
  end function wall_block_count

  !> Read and check the &wall group of `path` (absent: no wall).
  subroutine read_wall_config(path, w, status)
    character(len=*), intent(in) :: path
    type(wall_config_t), intent(out) :: w
    type(status_t), intent(inout) :: status
    integer :: unit, ios, courses, blocks_per_course
    real(dp) :: block_width_m, block_height_m
    character(len=16) :: bond
    character(len=512) :: iomsg
    namelist /wall/ courses, blocks_per_course, block_width_m, block_height_m, bond

    if (.not. status%ok) return
    call check_names(path, 'wall', [character(len=24) :: 'courses', 'blocks_per_course', 'block_width_m', &
                                    'block_height_m', 'bond'], status)
    if (.not. status%ok) return
    courses = w%courses; blocks_per_course = w%blocks_per_course; block_width_m = w%block_width_m
    block_height_m = w%block_height_m; bond = w%bond
    open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      call fail(status, trim(path)//': cannot open input: '//trim(iomsg))
      return
    end if
    read (unit, nml=wall, iostat=ios, iomsg=iomsg)
    close (unit)
    if (ios /= 0 .and. ios /= iostat_end) then
      call fail(status, trim(path)//': in namelist group &wall: '//trim(iomsg)// &
                ". The variables of &wall are: courses, blocks_per_course (integer), block_width_m, "// &
                "block_height_m (real, m), bond ('running'|'stack')")
      return
    end if
    w = wall_config_t(courses, blocks_per_course, block_width_m, block_height_m, lower(bond))
    if (w%courses == 0) return
    call need(w%courses >= 1 .and. w%courses <= 10000, 'courses', real(w%courses, dp), '1 <= courses <= 10000')
    call need(w%blocks_per_course >= 1 .and. w%blocks_per_course <= 10000, 'blocks_per_course', &
              real(w%blocks_per_course, dp), '1 <= blocks_per_course <= 10000')
    ! At least 0.1 mm, as the blocks of a polygon file (a 1e-9 m wall "collapsed" at once).
    call need(w%block_width_m >= 1.0e-4_dp .and. w%block_width_m <= 100.0_dp, 'block_width_m', w%block_width_m, &
              '1e-4 m <= block_width_m <= 100 m')
    call need(w%block_height_m >= 1.0e-4_dp .and. w%block_height_m <= 100.0_dp, 'block_height_m', &
              w%block_height_m, '1e-4 m <= block_height_m <= 100 m')
    if (.not. status%ok) return
    if (w%bond /= 'running' .and. w%bond /= 'stack') then
      call fail(status, trim(path)//": &wall bond = '"//trim(w%bond)//"' is not one of 'running', 'stack'")
      return
    end if
    if (wall_block_count(w) > max_wall_blocks) &
      call fail(status, trim(path)//': &wall of '//itoa(w%courses)//' courses x '//itoa(w%blocks_per_course)// &
                ' blocks has more than '//itoa(max_wall_blocks)//' blocks')

  contains

    subroutine need(good, name, value, allowed)
      logical, intent(in) :: good
      character(len=*), intent(in) :: name, allowed
      real(dp), intent(in) :: value
      if (good .or. .not. status%ok) return
      call fail(status, trim(path)//': &wall '//name//' = '//fmt_real(value)//' is outside the allowed range '// &
                allowed)
    end subroutine need

  end subroutine read_wall_config

end module voussoir_wall_config
