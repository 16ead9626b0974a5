!> The top surface of an assembly of blocks (the highest boundary point of any block at an
!> x, and that block) and the block that contains a point: where voussoir_placed_loads
!> stands loads and spreads them.
module voussoir_top_surface
  use voussoir_kinds, only: dp
  use voussoir_text, only: fmt_significant
  use voussoir_geometry, only: cross2
  use voussoir_assembly, only: assembly_t
  implicit none
  private
  public :: boundary_tol_m, block_at, top_surface, span_text

  real(dp), parameter :: boundary_tol_m = 1.0e-9_dp   !! a point this close outside a block is on it

contains

  !> 'x from a to b m' over every block.
  function span_text(asm) result(text)
    type(assembly_t), intent(in) :: asm
    character(len=:), allocatable :: text
    real(dp) :: lo, hi
    integer :: b
    lo = huge(1.0_dp)
    hi = -huge(1.0_dp)
    do b = 1, asm%n_bodies
      lo = min(lo, minval(asm%polygon(b)%xy(1, :)))
      hi = max(hi, maxval(asm%polygon(b)%xy(1, :)))
    end do
    text = 'x from '//fmt_significant(lo, 6)//' to '//fmt_significant(hi, 6)//' m'
  end function span_text

  !> The block that contains `p` (convex, counter-clockwise polygons; a point within
  !> boundary_tol_m outside counts), a free block before a driven one; 0 if none.
  pure integer function block_at(asm, p) result(found)
    type(assembly_t), intent(in) :: asm
    real(dp), intent(in) :: p(2)
    integer :: b, k, nv
    real(dp) :: e(2)
    logical :: inside
    found = 0
    do b = 1, asm%n_bodies
      associate (xy => asm%polygon(b)%xy)
        nv = size(xy, 2)
        inside = .true.
        do k = 1, nv
          e = xy(:, modulo(k, nv) + 1) - xy(:, k)
          if (cross2(e, p - xy(:, k))/norm2(e) < -boundary_tol_m) inside = .false.
        end do
      end associate
      if (.not. inside) cycle
      if (found == 0) found = b
      if (asm%driven(found) .and. .not. asm%driven(b)) found = b
    end do
  end function block_at

  !> The top surface of the assembly at `x`: the highest boundary point `y` of any block
  !> there and that `block` (a free block before a driven one at the same height).
  pure subroutine top_surface(asm, x, y, block, found)
    type(assembly_t), intent(in) :: asm
    real(dp), intent(in) :: x
    real(dp), intent(out) :: y
    integer, intent(out) :: block
    logical, intent(out) :: found
    real(dp) :: a(2), c(2), t, yk
    integer :: b, k, nv
    found = .false.
    block = 0
    y = -huge(1.0_dp)
    do b = 1, asm%n_bodies
      associate (xy => asm%polygon(b)%xy)
        nv = size(xy, 2)
        do k = 1, nv
          a = xy(:, k)
          c = xy(:, modulo(k, nv) + 1)
          if (x < min(a(1), c(1)) - boundary_tol_m .or. x > max(a(1), c(1)) + boundary_tol_m) cycle
          if (abs(c(1) - a(1)) <= boundary_tol_m) then
            yk = max(a(2), c(2))
          else
            t = min(1.0_dp, max(0.0_dp, (x - a(1))/(c(1) - a(1))))
            yk = a(2) + t*(c(2) - a(2))
          end if
          if (.not. found .or. yk > y + boundary_tol_m .or. &
              (yk >= y - boundary_tol_m .and. asm%driven(block) .and. .not. asm%driven(b))) then
            y = max(y, yk)
            block = b
            found = .true.
          end if
        end do
      end associate
    end do
  end subroutine top_surface

end module voussoir_top_surface
