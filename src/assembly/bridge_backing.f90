!> Masonry backing over the haunches of a bridge (issue 37; docs/bridges.md, "Backing"):
!> the region between the bottom polyline (the abutments' and piers' tops and the rings'
!> extrados, x-monotone) and a level `level_m` below the crowns, cut into convex blocks in
!> horizontal courses, as backing is laid ("rubble laid in horizontal courses abutting
!> against the arch ring", Baker, A Treatise on Masonry Construction, 1909).
!>
!> The scheme, convex by construction:
!> 1. Every segment of the bottom that lies at or below the level is a column. A segment
!>    that crosses the level is left bare: the backing stops at the last joint whose
!>    extrados end is below the level, so that a voussoir is backed over its whole
!>    extrados or not at all (a face half under the backing and half under the fill
!>    would be neither's top surface).
!> 2. In each column, the bottom piece from the segment up to the lowest course line
!>    (level_m less a whole number of `course_m`) that stands at least min_fraction x
!>    course_m above the segment's higher end (the level itself where none does): a
!>    trapezoid, or a triangle where the segment touches the level at one end.
!> 3. Rectangles of height course_m above it, up to the level.
!> The columns' vertical sides meet those of their neighbours, the courses' beds at the
!> same heights; the pieces tile the region.
module voussoir_bridge_backing
  use voussoir_kinds, only: dp
  use voussoir_assembly, only: polygon_t
  implicit none
  private
  public :: cut_backing, backing_region_area

  !> No bottom piece lower than this fraction of a course at its higher end, unless the
  !> whole column is.
  real(dp), parameter :: min_fraction = 0.3_dp
  real(dp), parameter :: same_m = 1.0e-12_dp   !! columns narrower, or sides lower, than this are none

contains

  !> The blocks of the backing over `bottom` (2, n: x ascending) up to `level_m`, in
  !> courses of `course_m` [m]; none where the bottom stands at or above the level.
  pure function cut_backing(bottom, level_m, course_m) result(blocks)
    real(dp), intent(in) :: bottom(:, :), level_m, course_m
    type(polygon_t), allocatable :: blocks(:)
    real(dp) :: a(2), b(2), top, y_lo, y_hi
    integer :: k, j, i
    allocate (blocks(0))
    do k = 1, size(bottom, 2) - 1
      a = bottom(:, k)
      b = bottom(:, k + 1)
      if (max(a(2), b(2)) > level_m .or. b(1) - a(1) <= same_m) cycle
      j = max(0, floor((level_m - (max(a(2), b(2)) + min_fraction*course_m))/course_m))
      top = level_m - j*course_m
      if (top - a(2) <= same_m) then        ! the segment ends on the level at its left end
        blocks = [blocks, polygon_t(reshape([a, b, b(1), top], [2, 3]))]
      else if (top - b(2) <= same_m) then   ! ... or at its right end
        blocks = [blocks, polygon_t(reshape([a, b, a(1), top], [2, 3]))]
      else
        blocks = [blocks, polygon_t(reshape([a, b, b(1), top, a(1), top], [2, 4]))]
      end if
      do i = 0, j - 1   ! course i: from level - (i + 1) course to level - i course
        y_lo = level_m - (i + 1)*course_m
        y_hi = level_m - i*course_m
        blocks = [blocks, polygon_t(reshape([a(1), y_lo, b(1), y_lo, b(1), y_hi, a(1), y_hi], [2, 4]))]
      end do
    end do
  end function cut_backing

  !> The area of the backing's region [m2]: over every segment of the bottom at or below
  !> the level, the trapezoid between it and the level.
  pure real(dp) function backing_region_area(bottom, level_m) result(area)
    real(dp), intent(in) :: bottom(:, :), level_m
    integer :: k
    area = 0.0_dp
    do k = 1, size(bottom, 2) - 1
      if (max(bottom(2, k), bottom(2, k + 1)) > level_m) cycle
      area = area + (bottom(1, k + 1) - bottom(1, k))*(level_m - 0.5_dp*(bottom(2, k) + bottom(2, k + 1)))
    end do
  end function backing_region_area

end module voussoir_bridge_backing
