!> Plane geometry of convex polygons: area, centroid, inertia, orientation.
!>
!> Polygons are (2, n) arrays of vertices in counter-clockwise order.
module voussoir_geometry
  use voussoir_kinds, only: dp, pi
  implicit none
  private

  public :: polygon_area, polygon_centroid, polygon_polar_moment, cross2, rotate2, &
            is_convex_ccw, overlap_depth, polygon_min_width

contains

  !> z-component of the cross product of two plane vectors.
  pure real(dp) function cross2(a, b)
    real(dp), intent(in) :: a(2), b(2)
    cross2 = a(1)*b(2) - a(2)*b(1)
  end function cross2

  !> Vector `v` rotated by `angle_rad` counter-clockwise.
  pure function rotate2(v, angle_rad) result(w)
    real(dp), intent(in) :: v(2), angle_rad
    real(dp) :: w(2)
    w(1) = cos(angle_rad)*v(1) - sin(angle_rad)*v(2)
    w(2) = sin(angle_rad)*v(1) + cos(angle_rad)*v(2)
  end function rotate2

  !> Signed area [m2] (positive for counter-clockwise vertices).
  pure real(dp) function polygon_area(xy)
    real(dp), intent(in) :: xy(:, :)
    integer :: i, j, n
    n = size(xy, 2)
    polygon_area = 0.0_dp
    do i = 1, n
      j = merge(1, i + 1, i == n)
      polygon_area = polygon_area + cross2(xy(:, i), xy(:, j))
    end do
    polygon_area = 0.5_dp*polygon_area
  end function polygon_area

  !> Centroid [m] of the polygon's area.
  pure function polygon_centroid(xy) result(c)
    real(dp), intent(in) :: xy(:, :)
    real(dp) :: c(2), w
    integer :: i, j, n
    n = size(xy, 2)
    c = 0.0_dp
    do i = 1, n
      j = merge(1, i + 1, i == n)
      w = cross2(xy(:, i), xy(:, j))
      c = c + w*(xy(:, i) + xy(:, j))
    end do
    c = c/(6.0_dp*polygon_area(xy))
  end function polygon_centroid

  !> Polar second moment of area about the centroid [m4].
  pure real(dp) function polygon_polar_moment(xy)
    real(dp), intent(in) :: xy(:, :)
    real(dp) :: c(2), p(2), q(2), w
    integer :: i, j, n
    n = size(xy, 2)
    c = polygon_centroid(xy)
    polygon_polar_moment = 0.0_dp
    do i = 1, n
      j = merge(1, i + 1, i == n)
      p = xy(:, i) - c
      q = xy(:, j) - c
      w = cross2(p, q)
      polygon_polar_moment = polygon_polar_moment + w*(dot_product(p, p) + dot_product(p, q) &
                                                       + dot_product(q, q))
    end do
    polygon_polar_moment = polygon_polar_moment/12.0_dp
  end function polygon_polar_moment

  !> True when the polygon is strictly convex with counter-clockwise vertices: every
  !> turn is to the left and the turns add up to one revolution (a star polygon, whose
  !> edges cross, turns left at every vertex too but goes round twice or more).
  pure logical function is_convex_ccw(xy)
    real(dp), intent(in) :: xy(:, :)
    integer :: i, n
    real(dp) :: e_in(2), e_out(2), turning_rad
    n = size(xy, 2)
    is_convex_ccw = n >= 3
    if (.not. is_convex_ccw) return
    turning_rad = 0.0_dp
    do i = 1, n
      e_in = xy(:, modulo(i, n) + 1) - xy(:, i)
      e_out = xy(:, modulo(i + 1, n) + 1) - xy(:, modulo(i, n) + 1)
      if (.not. (cross2(e_in, e_out) > 0.0_dp)) then   ! (also false for a NaN)
        is_convex_ccw = .false.
        return
      end if
      turning_rad = turning_rad + atan2(cross2(e_in, e_out), dot_product(e_in, e_out))
    end do
    ! The turns of a simple polygon add up to 2 pi, those of a star to 4 pi or more.
    is_convex_ccw = turning_rad < 3.0_dp*pi
  end function is_convex_ccw

  !> Outward unit normals of the edges of a convex polygon (counter-clockwise), edge i
  !> from vertex i to i+1; zero for an edge of zero length.
  pure function edge_normals(xy) result(nrm)
    real(dp), intent(in) :: xy(:, :)
    real(dp) :: nrm(2, size(xy, 2))
    integer :: i, n
    real(dp) :: e(2)
    n = size(xy, 2)
    do i = 1, n
      e = xy(:, modulo(i, n) + 1) - xy(:, i)
      nrm(:, i) = 0.0_dp
      if (norm2(e) > 0.0_dp) nrm(:, i) = [e(2), -e(1)]/norm2(e)
    end do
  end function edge_normals

  !> The smallest width of a convex polygon (counter-clockwise) [m]: its least extent
  !> across any of its edges (the width between the tightest pair of parallel supports).
  pure real(dp) function polygon_min_width(xy)
    real(dp), intent(in) :: xy(:, :)
    real(dp) :: nrm(2, size(xy, 2)), along(size(xy, 2))
    integer :: i
    nrm = edge_normals(xy)
    polygon_min_width = huge(1.0_dp)
    do i = 1, size(xy, 2)
      if (all(nrm(:, i) == 0.0_dp)) cycle
      along = matmul(nrm(:, i), xy)
      polygon_min_width = min(polygon_min_width, maxval(along) - minval(along))
    end do
  end function polygon_min_width

  !> How deep two convex polygons (counter-clockwise) interpenetrate [m]: the smallest
  !> overlap of their projections over the edge normals of both (separating axes). Zero
  !> or negative when they touch or are apart.
  pure real(dp) function overlap_depth(a, b)
    real(dp), intent(in) :: a(:, :), b(:, :)
    real(dp) :: axes(2, size(a, 2) + size(b, 2)), pa(size(a, 2)), pb(size(b, 2))
    integer :: i
    axes = reshape([edge_normals(a), edge_normals(b)], shape(axes))
    overlap_depth = huge(1.0_dp)
    do i = 1, size(axes, 2)
      if (all(axes(:, i) == 0.0_dp)) cycle
      pa = matmul(axes(:, i), a)
      pb = matmul(axes(:, i), b)
      overlap_depth = min(overlap_depth, min(maxval(pa), maxval(pb)) - max(minval(pa), minval(pb)))
    end do
  end function overlap_depth

end module voussoir_geometry
