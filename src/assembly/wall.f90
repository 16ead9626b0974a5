!> Walls of bricks or stones laid dry, for the assemblies that arches are not: the
!> assembly that a &wall group (voussoir_wall_config) describes.
module voussoir_wall
  use voussoir_kinds, only: dp
  use voussoir_assembly, only: assembly_t, role_voussoir, role_foundation
  use voussoir_wall_config, only: wall_config_t, wall_block_count, bond_running
  implicit none
  private
  public :: build_wall, box, block_stack

contains

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
      offset = w%bond == bond_running .and. modulo(c, 2) == 1
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

  end subroutine build_wall

  !> A column of `n_blocks` blocks b x h, from x = 0 to b, on a driven base block (body 1)
  !> three blocks wide and one deep: the rocking block and the stacks of the limit
  !> analysis's closed forms.
  pure subroutine block_stack(b, h, n_blocks, asm)
    real(dp), intent(in) :: b, h
    integer, intent(in) :: n_blocks
    type(assembly_t), intent(out) :: asm
    integer :: k
    asm%n_bodies = n_blocks + 1
    allocate (asm%polygon(n_blocks + 1), asm%driven(n_blocks + 1), asm%role(n_blocks + 1))
    asm%polygon(1)%xy = box(-b, 2*b, -h, 0.0_dp)
    asm%driven = .false.
    asm%driven(1) = .true.
    asm%role = role_voussoir
    asm%role(1) = role_foundation
    do k = 1, n_blocks
      asm%polygon(k + 1)%xy = box(0.0_dp, b, (k - 1)*h, k*h)
    end do
  end subroutine block_stack

  !> The corners (2, 4) of the axis-aligned rectangle [xa, xb] x [ya, yb], counter-clockwise
  !> from the lower left.
  pure function box(xa, xb, ya, yb) result(xy)
    real(dp), intent(in) :: xa, xb, ya, yb
    real(dp) :: xy(2, 4)
    xy = reshape([xa, ya, xb, ya, xb, yb, xa, yb], [2, 4])
  end function box

end module voussoir_wall
