!> The fill of a bridge cut into particles (issue 37, item 2(b); docs/bridges.md, "Fill as
!> particles"): the region between a bottom polyline (the abutments' tops and the rings'
!> extrados, x-monotone from the left wall to the right one) and the fill's level, cut into
!> small convex blocks.
!>
!> The scheme, convex by construction and without slivers:
!> 1. Columns: the x of every vertex of the bottom, and a grid of spacing `size_m` from the
!>    left end, a grid line dropped where it falls within `min_fraction` x size of a vertex.
!>    Within a column the bottom is one straight segment.
!> 2. A conforming bottom layer: in each column, the trapezoid from the bottom segment up to
!>    the lowest row line (the level less a whole number of sizes) that stands at least
!>    `min_fraction` x size above the segment's higher end (the level itself where none
!>    does). Two vertical sides, a level top: convex.
!> 3. Staggered rows of height `size_m` down from the level, each over the columns whose
!>    bottom layer ends at or below the row's foot; their cuts at the grid, shifted by half a
!>    size every other row (a running bond), a cut dropped within `min_fraction` x size of
!>    the interval's ends or the previous cut: rectangles.
!> The pieces tile the region exactly (their areas sum to the region's shoelace area).
module voussoir_fill_particles
  use voussoir_kinds, only: dp
  use voussoir_assembly, only: polygon_t
  implicit none
  private
  public :: cut_fill_particles, fill_region_area, min_fraction

  !> No piece narrower (a cut) or lower (the bottom layer) than this fraction of the size,
  !> unless two vertices of the bottom stand closer than that.
  real(dp), parameter :: min_fraction = 0.3_dp
  real(dp), parameter :: same_x_m = 1.0e-12_dp   !! columns narrower than this are none

contains

  !> The particles of the region over `bottom` (2, n: x ascending, from the left end to the
  !> right end, every y below `level_m`) up to `level_m`, of size `size_m` [m].
  pure function cut_fill_particles(bottom, level_m, size_m) result(particles)
    real(dp), intent(in) :: bottom(:, :), level_m, size_m
    type(polygon_t), allocatable :: particles(:)
    real(dp), allocatable :: col_x(:), col_top(:)
    integer, allocatable :: col_row(:)
    real(dp) :: xa, xb, fa, fb, top, y_hi, y_lo, shift, p, q
    integer :: c, j, j_max, c0, c1

    col_x = column_breaks(bottom, size_m)
    allocate (particles(0), col_top(size(col_x) - 1), col_row(size(col_x) - 1))
    ! The bottom layer: one trapezoid per column; col_row the row lines it reaches up to.
    do c = 1, size(col_x) - 1
      xa = col_x(c)
      xb = col_x(c + 1)
      col_row(c) = -1
      if (xb - xa <= same_x_m) cycle
      fa = bottom_y(bottom, xa)
      fb = bottom_y(bottom, xb)
      col_row(c) = max(0, floor((level_m - (max(fa, fb) + min_fraction*size_m))/size_m))
      top = level_m - col_row(c)*size_m
      col_top(c) = top
      particles = [particles, polygon_t(reshape([xa, fa, xb, fb, xb, top, xa, top], [2, 4]))]
    end do
    ! The staggered rows above it: row j between level - (j+1) size and level - j size.
    j_max = maxval(col_row) - 1
    do j = 0, j_max
      y_hi = level_m - j*size_m
      y_lo = y_hi - size_m
      shift = 0.5_dp*size_m*modulo(j, 2)
      c = 1
      do while (c <= size(col_row))
        if (col_row(c) < j + 1) then   ! (a column of no width has col_row -1: not free)
          c = c + 1
          cycle
        end if
        c0 = c
        do while (c <= size(col_row))
          if (col_row(c) < j + 1 .and. col_x(c + 1) - col_x(c) > same_x_m) exit
          c = c + 1
        end do
        c1 = c - 1
        p = col_x(c0)
        q = col_x(c1 + 1)
        call add_row_interval(p, q, y_lo, y_hi, bottom(1, 1) + shift, size_m, particles)
      end do
    end do
  end function cut_fill_particles

  !> The rectangles of a row from `y_lo` to `y_hi` over [a, b], cut at the grid x0 + i size
  !> (a cut within min_fraction x size of a, b or the previous cut dropped), appended.
  pure subroutine add_row_interval(a, b, y_lo, y_hi, x0, size_m, particles)
    real(dp), intent(in) :: a, b, y_lo, y_hi, x0, size_m
    type(polygon_t), allocatable, intent(inout) :: particles(:)
    real(dp) :: left, cut
    integer :: i
    left = a
    i = ceiling((a - x0)/size_m)
    do
      cut = x0 + i*size_m
      i = i + 1
      if (cut >= b - min_fraction*size_m) exit
      if (cut - left < min_fraction*size_m) cycle
      particles = [particles, polygon_t(reshape([left, y_lo, cut, y_lo, cut, y_hi, left, y_hi], [2, 4]))]
      left = cut
    end do
    particles = [particles, polygon_t(reshape([left, y_lo, b, y_lo, b, y_hi, left, y_hi], [2, 4]))]
  end subroutine add_row_interval

  !> The x where columns break: every vertex of the bottom, and the grid of `size_m` from
  !> its left end where it is not within min_fraction x size of a vertex; ascending.
  pure function column_breaks(bottom, size_m) result(x)
    real(dp), intent(in) :: bottom(:, :), size_m
    real(dp), allocatable :: x(:)
    real(dp) :: g, key
    integer :: i, n, k
    x = [bottom(1, 1)]
    do k = 2, size(bottom, 2)
      if (bottom(1, k) - x(size(x)) > same_x_m) x = [x, bottom(1, k)]
    end do
    n = ceiling((bottom(1, size(bottom, 2)) - bottom(1, 1))/size_m)
    do i = 1, n - 1
      g = bottom(1, 1) + i*size_m
      if (minval(abs(bottom(1, :) - g)) < min_fraction*size_m) cycle
      x = [x, g]
    end do
    ! Insertion sort: a few hundred entries.
    do i = 2, size(x)
      key = x(i)
      k = i - 1
      do while (k >= 1)
        if (x(k) <= key) exit
        x(k + 1) = x(k)
        k = k - 1
      end do
      x(k + 1) = key
    end do
  end function column_breaks

  !> The bottom's y at `x` (linear between its vertices; at a vertex, its own y).
  pure real(dp) function bottom_y(bottom, x)
    real(dp), intent(in) :: bottom(:, :), x
    integer :: k
    bottom_y = bottom(2, size(bottom, 2))
    do k = 1, size(bottom, 2) - 1
      if (x <= bottom(1, k + 1)) then
        if (x <= bottom(1, k)) then
          bottom_y = bottom(2, k)
        else
          bottom_y = bottom(2, k) + (x - bottom(1, k))*(bottom(2, k + 1) - bottom(2, k))/(bottom(1, k + 1) - bottom(1, k))
        end if
        return
      end if
    end do
  end function bottom_y

  !> The area of the region between `bottom` and `level_m` [m2] (shoelace, the polygon of
  !> the bottom closed along the level).
  pure real(dp) function fill_region_area(bottom, level_m)
    real(dp), intent(in) :: bottom(:, :), level_m
    real(dp), allocatable :: xy(:, :)
    integer :: k, n
    n = size(bottom, 2)
    xy = reshape([bottom, bottom(1, n), level_m, bottom(1, 1), level_m], [2, n + 2])
    fill_region_area = 0.0_dp
    do k = 1, n + 2
      associate (a => xy(:, k), b => xy(:, modulo(k, n + 2) + 1))
        fill_region_area = fill_region_area + 0.5_dp*(a(1)*b(2) - b(1)*a(2))
      end associate
    end do
  end function fill_region_area

end module voussoir_fill_particles
