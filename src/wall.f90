!> Walls of bricks or stones laid dry, for the assemblies that arches are not: the &wall
!> group (courses of equal blocks, in running or stack bond, on one driven foundation)
!> and the assembly it describes.
module voussoir_wall
  use, intrinsic :: iso_fortran_env, only: iostat_end
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa, fmt_real, lower
  use voussoir_namelist_check, only: check_names
  use voussoir_assembly, only: assembly_t, role_voussoir, role_foundation
  implicit none
  private
  public :: wall_config_t, read_wall_config, build_wall, wall_block_count

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

  !> The wall of `w` standing on a driven foundation whose top is y = 0, the wall's left
  !> end at x = 0. Bodies: the foundation first, then the blocks course by course from
  !> the bottom, left to right.
  subroutine build_wall(w, assembly)
    type(wall_config_t), intent(in) :: w
    type(assembly_t), intent(out) :: assembly
    integer :: nb, c, k, b, n_in_course
    real(dp) :: length, x0, x1, y0, y1, bw, bh
    logical :: offset

    bw = w%block_width_m
    bh = w%block_height_m
    length = w%blocks_per_course*bw
    nb = 1 + wall_block_count(w)
    allocate (assembly%polygon(nb), assembly%driven(nb), assembly%role(nb), assembly%course(nb))
    assembly%n_bodies = nb
    assembly%polygon(1)%xy = box(-bw, length + bw, -bh, 0.0_dp)
    assembly%driven = .false.
    assembly%driven(1) = .true.
    assembly%role = role_voussoir
    assembly%role(1) = role_foundation
    assembly%course(1) = 0
    b = 1
    do c = 0, w%courses - 1
      y0 = c*bh
      y1 = y0 + bh
      offset = w%bond == 'running' .and. modulo(c, 2) == 1
      n_in_course = w%blocks_per_course + merge(1, 0, offset)
      do k = 1, n_in_course
        if (offset) then
          x0 = max(0.0_dp, (k - 1.5_dp)*bw)
          x1 = min(length, (k - 0.5_dp)*bw)
        else
          x0 = (k - 1)*bw
          x1 = k*bw
        end if
        b = b + 1
        assembly%polygon(b)%xy = box(x0, x1, y0, y1)
        assembly%course(b) = c + 1
      end do
    end do

  contains

    pure function box(xa, xb, ya, yb) result(xy)
      real(dp), intent(in) :: xa, xb, ya, yb
      real(dp) :: xy(2, 4)
      xy = reshape([xa, ya, xb, ya, xb, yb, xa, yb], [2, 4])
    end function box

  end subroutine build_wall

end module voussoir_wall
