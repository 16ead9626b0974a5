!> The bridge builder (src/assembly/bridge.f90) against closed forms: each shape's
!> intrados recovered from the joints it builds (a semicircle's areas, a segmental arch's
!> span and rise from the circle through three of its joints, the equilateral pointed
!> arch's centres and apex, the ellipse's and the parabola's equations and equal arc
!> lengths measured here by a fine polyline), and the parts of a two-span bridge; the fill
!> cut into particles over a hump whose area is known by hand, and a bridge's particles;
!> the backing in courses over a hump (by hand) and over a bridge's haunches.
program test_bridge
  use voussoir_kinds, only: dp, pi
  use voussoir_status, only: status_t
  use voussoir_geometry, only: polygon_area, is_convex_ccw
  use voussoir_assembly, only: assembly_t, polygon_t, role_voussoir, role_foundation, role_fill, role_backing
  use voussoir_bridge_backing, only: cut_backing, backing_region_area
  use voussoir_fill_particles, only: cut_fill_particles, fill_region_area, min_fraction
  use voussoir_bridge_config, only: bridge_config_t
  use voussoir_bridge, only: build_bridge, bridge_ring_joints
  use voussoir_bodies, only: bodies_t, bodies_init
  use voussoir_contact_law, only: contact_law_t, contact_law_init, pair_friction_of
  use voussoir_assert, only: assert_true, assert_close, assert_summary
  implicit none

  call test_semicircle_areas()
  call test_segmental_span_and_rise()
  call test_pointed_equilateral()
  call test_three_centred()
  call test_elliptical_and_parabolic()
  call test_two_spans_on_a_pier()
  call test_particles_over_a_hump()
  call test_bridge_with_particles()
  call test_backing_over_a_hump()
  call test_bridge_with_backing()
  call assert_summary()

contains

  !> The region over a hump, from (0, 0) level to (1, 0), up to (2, 1), down to (3, 0), level
  !> to (4, 0), under a level at y = 2: 4 x 2 less the triangle (base 2, height 1), 7 m2 by
  !> hand. Cut at size 0.3 m: every particle convex, counter-clockwise, at least
  !> min_fraction x size high and wide (no two vertices of the hump closer than that), their
  !> areas summing to 7 m2 (1e-12); the shoelace of the region gives 7 too.
  subroutine test_particles_over_a_hump()
    real(dp), parameter :: size_m = 0.3_dp
    real(dp) :: hump(2, 5), total, least_height, least_width
    type(polygon_t), allocatable :: parts(:)
    integer :: k
    logical :: convex
    hump = reshape([0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 2.0_dp, 1.0_dp, 3.0_dp, 0.0_dp, 4.0_dp, 0.0_dp], [2, 5])
    parts = cut_fill_particles(hump, 2.0_dp, size_m)
    total = 0.0_dp
    convex = .true.
    least_height = huge(1.0_dp)
    least_width = huge(1.0_dp)
    do k = 1, size(parts)
      total = total + polygon_area(parts(k)%xy)
      convex = convex .and. is_convex_ccw(parts(k)%xy) .and. polygon_area(parts(k)%xy) > 0.0_dp
      least_height = min(least_height, maxval(parts(k)%xy(2, :)) - minval(parts(k)%xy(2, :)))
      least_width = min(least_width, maxval(parts(k)%xy(1, :)) - minval(parts(k)%xy(1, :)))
    end do
    call assert_true(size(parts) > 60, 'particles over a hump: more than 60 (7 m2 / 0.09 m2 is 78)')
    call assert_true(convex, 'particles over a hump: every one convex, counter-clockwise, of positive area')
    call assert_close(total, 7.0_dp, 'particles over a hump: their areas sum to 4 x 2 - 1 m2', rtol=1.0e-12_dp)
    call assert_close(fill_region_area(hump, 2.0_dp), 7.0_dp, 'the region over a hump by shoelace', rtol=1.0e-12_dp)
    call assert_true(least_height >= min_fraction*size_m - 1.0e-12_dp .and. &
                     least_width >= min_fraction*size_m - 1.0e-12_dp, 'particles over a hump: no sliver')
  end subroutine test_particles_over_a_hump

  !> A segmental span with its fill as 0.5 m particles: the ring and abutments as without,
  !> then free particles (role_fill) of the fill's density and friction, no engineers' fill
  !> (has_fill false); the particles' area the fill's over the extrados chords and the
  !> abutments' level tops (shoelace here, from the ring's joints).
  subroutine test_bridge_with_particles()
    type(bridge_config_t) :: b
    type(assembly_t) :: asm
    type(status_t) :: status
    real(dp) :: inner(2, 0:12), outer(2, 0:12), area, total
    real(dp), allocatable :: region(:, :)
    integer :: k
    b = one_span('segmental', 10.0_dp, 2.5_dp, 0.45_dp, 12)
    b%abutment_width_m = 2.0_dp
    b%fill_density_kg_m3 = 1900.0_dp
    b%fill_level_m = 3.45_dp
    b%fill_model = 'particles'
    b%fill_particle_size_m = 0.5_dp
    b%fill_particle_friction = 0.45_dp
    call build_bridge(b, asm, status)
    call assert_true(status%ok, 'bridge with particles: built')
    call assert_true(.not. asm%has_fill .and. all(asm%role(15:) == role_fill) .and. all(.not. asm%driven(15:)) .and. &
                     asm%n_bodies > 14 + 50 .and. all(asm%role(1:12) == role_voussoir) .and. &
                     all(asm%role(13:14) == role_foundation), &
                     'bridge with particles: 12 voussoirs, 2 abutments, then free particles, no columns')
    call assert_true(all(asm%density_kg_m3(15:) == 1900.0_dp) .and. all(asm%friction(15:) == 0.45_dp) .and. &
                     asm%block_name(15) == 'fill particle 1', "bridge with particles: the fill's density and friction")
    call bridge_ring_joints(b, 1, inner, outer)
    region = reshape([[-2.0_dp, outer(2, 0)], reshape(outer, [26]), [12.0_dp, outer(2, 12)], [12.0_dp, 3.45_dp], &
                      [-2.0_dp, 3.45_dp]], [2, 17])
    area = polygon_area(region)
    total = 0.0_dp
    do k = 15, asm%n_bodies
      total = total + polygon_area(asm%polygon(k)%xy)
    end do
    call assert_close(total, area, 'bridge with particles: they fill the region over the extrados', rtol=1.0e-12_dp)
  end subroutine test_bridge_with_particles

  !> Backing to y = 0.5 over a hump (0, 0), (1, 0), (1.5, 0.5), (2, 1), (2.5, 0.5), (3, 0),
  !> (4, 0): the segments at or below the level are [0, 1] and [3, 4] (0.5 m2 each) and the
  !> two that touch it, [1, 1.5] and [2.5, 3] (triangles of 0.125 m2); the two that cross
  !> it are left bare: 1.25 m2 by hand. In courses of 0.2 m: the level ones a bottom piece
  !> of 0.1 m and two courses (3 pieces each), the touching ones one triangle each: 8
  !> pieces, convex, counter-clockwise, none above the level.
  subroutine test_backing_over_a_hump()
    real(dp) :: hump(2, 7), total
    type(polygon_t), allocatable :: parts(:)
    integer :: k
    logical :: convex, below
    hump = reshape([0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 1.5_dp, 0.5_dp, 2.0_dp, 1.0_dp, 2.5_dp, 0.5_dp, 3.0_dp, 0.0_dp, &
                    4.0_dp, 0.0_dp], [2, 7])
    parts = cut_backing(hump, 0.5_dp, 0.2_dp)
    total = 0.0_dp
    convex = .true.
    below = .true.
    do k = 1, size(parts)
      total = total + polygon_area(parts(k)%xy)
      convex = convex .and. is_convex_ccw(parts(k)%xy) .and. polygon_area(parts(k)%xy) > 0.0_dp
      below = below .and. maxval(parts(k)%xy(2, :)) <= 0.5_dp + 1.0e-15_dp
    end do
    call assert_true(size(parts) == 8, 'backing over a hump: 3 + 1 + 1 + 3 pieces')
    call assert_true(convex .and. below, 'backing over a hump: every piece convex, counter-clockwise, below the level')
    call assert_close(total, 1.25_dp, 'backing over a hump: 2 x 0.5 + 2 x 0.125 m2 by hand', rtol=1.0e-12_dp)
    call assert_close(backing_region_area(hump, 0.5_dp), 1.25_dp, 'backing over a hump: its region', rtol=1.0e-12_dp)
  end subroutine test_backing_over_a_hump

  !> A segmental span with backing to 1.5 m: the ring and abutments as without, then free
  !> blocks (role_backing) of the backing's density and friction, named 'backing k', their
  !> area the trapezoids between the level and the abutments' tops and the extrados chords
  !> wholly below it (from the ring's joints, here).
  subroutine test_bridge_with_backing()
    type(bridge_config_t) :: b
    type(assembly_t) :: asm
    type(status_t) :: status
    real(dp) :: inner(2, 0:12), outer(2, 0:12), area, total
    integer :: k
    b = one_span('segmental', 10.0_dp, 2.5_dp, 0.45_dp, 12)
    b%abutment_width_m = 2.0_dp
    b%backing_level_m = 1.5_dp
    b%backing_course_m = 0.3_dp
    b%backing_density_kg_m3 = 2100.0_dp
    b%backing_friction = 0.5_dp
    call build_bridge(b, asm, status)
    call assert_true(status%ok, 'bridge with backing: built')
    call assert_true(asm%n_bodies > 14 + 8 .and. all(asm%role(15:) == role_backing) .and. all(.not. asm%driven(15:)) &
                     .and. all(asm%role(1:12) == role_voussoir) .and. all(asm%role(13:14) == role_foundation), &
                     'bridge with backing: 12 voussoirs, 2 abutments, then free backing blocks')
    call assert_true(all(asm%density_kg_m3(15:) == 2100.0_dp) .and. all(asm%friction(15:) == 0.5_dp) .and. &
                     asm%block_name(15) == 'backing 1', "bridge with backing: the backing's density and friction")
    call bridge_ring_joints(b, 1, inner, outer)
    ! The abutments' level tops, from their backs (x = -2 and 12 m) to the springing joints'
    ! extrados ends, at those ends' height; then the chords.
    area = (outer(1, 0) + 2.0_dp)*(1.5_dp - outer(2, 0)) + (12.0_dp - outer(1, 12))*(1.5_dp - outer(2, 12))
    do k = 1, 12
      if (max(outer(2, k - 1), outer(2, k)) > 1.5_dp) cycle
      area = area + abs(outer(1, k) - outer(1, k - 1))*(1.5_dp - 0.5_dp*(outer(2, k - 1) + outer(2, k)))
    end do
    total = 0.0_dp
    do k = 15, asm%n_bodies
      total = total + polygon_area(asm%polygon(k)%xy)
    end do
    call assert_close(total, area, 'bridge with backing: it fills the region over the abutments and the backed chords', &
                      rtol=1.0e-12_dp)
  end subroutine test_bridge_with_backing

  !> One span of `shape`.
  function one_span(shape, span_m, rise_m, thickness_m, n) result(b)
    character(len=*), intent(in) :: shape
    real(dp), intent(in) :: span_m, rise_m, thickness_m
    integer, intent(in) :: n
    type(bridge_config_t) :: b
    b%shape = shape
    b%span_m(1) = span_m
    b%rise_m(1) = rise_m
    b%ring_thickness_m = thickness_m
    b%n_voussoirs = n
    b%n_spans = 1
    b%abutment_width_m = 1.0_dp
  end function one_span

  !> A semicircle of intrados radius R_i = 0.85 m, R_e = 1 m: its n chord-faced voussoirs
  !> add up to (n/2)(R_e^2 - R_i^2) sin(pi/n) exactly, and tend to the annulus's half,
  !> pi (R_e^2 - R_i^2)/2, as n grows (the chords cut 1 - sin(x)/x, x = pi/n, about pi^2/(6 n^2)).
  subroutine test_semicircle_areas()
    type(assembly_t) :: a
    type(status_t) :: status
    real(dp), parameter :: ri = 0.85_dp, re = 1.0_dp
    real(dp) :: total
    integer :: n, k
    do n = 16, 200, 184
      call build_bridge(one_span('semicircular', 2*ri, ri, re - ri, n), a, status)
      call assert_true(status%ok .and. a%n_bodies == n + 2, 'bridge: a semicircle of voussoirs and two abutments')
      total = 0.0_dp
      do k = 1, n
        total = total + polygon_area(a%polygon(k)%xy)
        call assert_close(norm2(a%polygon(k)%xy(:, 1) - [ri, 0.0_dp]), ri, 'bridge: semicircle intrados radius', &
                          rtol=1.0e-14_dp)
        call assert_close(norm2(a%polygon(k)%xy(:, 4) - [ri, 0.0_dp]), re, 'bridge: semicircle extrados radius', &
                          rtol=1.0e-14_dp)
      end do
      call assert_close(total, 0.5_dp*n*(re**2 - ri**2)*sin(pi/n), 'bridge: semicircle voussoirs = chord polygons', &
                        rtol=1.0e-12_dp)
      call assert_close(total, 0.5_dp*pi*(re**2 - ri**2), 'bridge: semicircle voussoirs ~ half the annulus', &
                        rtol=1.1_dp*pi**2/(6.0_dp*n**2))
      call assert_true(all(a%driven(n + 1:n + 2)) .and. .not. any(a%driven(1:n)), 'bridge: abutments driven')
    end do
  end subroutine test_semicircle_areas

  !> Span 10 m, rise 2.5 m, 20 voussoirs: the circle through joints 1, 7 and 19 (none a
  !> springing nor the crown) gives back the span 2 sqrt(R^2 - y_c^2) and the rise R + y_c;
  !> the springings stand at x = 0 and 10 m, the crown joint at y = 2.5 m; the joints cut
  !> equal chords (equal arcs).
  subroutine test_segmental_span_and_rise()
    type(bridge_config_t) :: b
    real(dp) :: inner(2, 0:20), outer(2, 0:20), centre(2), r, chord(20)
    integer :: j
    b = one_span('segmental', 10.0_dp, 2.5_dp, 0.45_dp, 20)
    call bridge_ring_joints(b, 1, inner, outer)
    call circle_through(inner(:, 1), inner(:, 7), inner(:, 19), centre, r)
    call assert_close(2.0_dp*sqrt(r**2 - centre(2)**2), 10.0_dp, 'bridge: segmental span from its intrados', &
                      rtol=1.0e-12_dp)
    call assert_close(r + centre(2), 2.5_dp, 'bridge: segmental rise from its intrados', rtol=1.0e-12_dp)
    call assert_close(r, (25.0_dp + 2.5_dp**2)/5.0_dp, 'bridge: segmental radius (L^2/4 + r^2)/(2 r)', rtol=1.0e-12_dp)
    call assert_true(all(abs(inner(:, 0)) < 1.0e-15_dp) .and. abs(inner(1, 20) - 10.0_dp) < 1.0e-15_dp .and. &
                     abs(inner(2, 10) - 2.5_dp) < 1.0e-12_dp, 'bridge: segmental springings and crown')
    do j = 1, 20
      chord(j) = norm2(inner(:, j) - inner(:, j - 1))
      call assert_close(norm2(outer(:, j) - inner(:, j)), 0.45_dp, 'bridge: segmental joint = ring depth', &
                        rtol=1.0e-12_dp)
    end do
    call assert_true(maxval(chord) - minval(chord) < 1.0e-12_dp, 'bridge: segmental joints cut equal arcs')
  end subroutine test_segmental_span_and_rise

  !> The equilateral pointed arch (span 4 m, rise 4 sqrt(3)/2 m): each half's intrados on a
  !> circle of radius 4 m about the other springing; the apex joint vertical from (2, 2 sqrt 3)
  !> to where the two extrados circles of radius 4 + t about the springings meet.
  subroutine test_pointed_equilateral()
    type(bridge_config_t) :: b
    real(dp), parameter :: t = 0.3_dp
    real(dp) :: inner(2, 0:12), outer(2, 0:12)
    integer :: j
    b = one_span('pointed', 4.0_dp, 2.0_dp*sqrt(3.0_dp), t, 12)
    call bridge_ring_joints(b, 1, inner, outer)
    do j = 0, 6
      call assert_close(norm2(inner(:, j) - [4.0_dp, 0.0_dp]), 4.0_dp, 'bridge: pointed left half about (L, 0)', &
                        rtol=1.0e-13_dp)
      call assert_close(norm2(inner(:, 12 - j)), 4.0_dp, 'bridge: pointed right half about (0, 0)', rtol=1.0e-13_dp)
    end do
    call assert_close(inner(2, 6), 2.0_dp*sqrt(3.0_dp), 'bridge: pointed crown height L sqrt(3)/2', rtol=1.0e-13_dp)
    call assert_close(norm2(outer(:, 6)), 4.0_dp + t, 'bridge: pointed extrados apex on the right extrados circle', &
                      rtol=1.0e-13_dp)
    call assert_close(norm2(outer(:, 6) - [4.0_dp, 0.0_dp]), 4.0_dp + t, 'bridge: ... and on the left one', &
                      rtol=1.0e-13_dp)
    call assert_close(outer(1, 6), 2.0_dp, 'bridge: pointed apex joint vertical', atol=1.0e-13_dp)
  end subroutine test_pointed_equilateral

  !> Span 10 m, rise 3 m: the crown at (5, 3), vertical at the springings (level springing
  !> joints), the intrados turning the same way all along (convex ring).
  subroutine test_three_centred()
    type(bridge_config_t) :: b
    real(dp) :: inner(2, 0:18), outer(2, 0:18)
    type(assembly_t) :: a
    type(status_t) :: status
    integer :: j
    b = one_span('three-centred', 10.0_dp, 3.0_dp, 0.4_dp, 18)
    call bridge_ring_joints(b, 1, inner, outer)
    call assert_close(inner(2, 9), 3.0_dp, 'bridge: three-centred crown height', rtol=1.0e-13_dp)
    call assert_close(inner(1, 9), 5.0_dp, 'bridge: three-centred crown at midspan', rtol=1.0e-13_dp)
    call assert_true(outer(2, 0) == 0.0_dp .and. outer(2, 18) == 0.0_dp .and. abs(outer(1, 0) + 0.4_dp) < 1.0e-13_dp, &
                     'bridge: three-centred springing joints level')
    call build_bridge(b, a, status)
    call assert_true(status%ok, 'bridge: three-centred built')
    do j = 1, 18
      call assert_true(is_convex_ccw(a%polygon(j)%xy), 'bridge: three-centred voussoirs convex')
    end do
  end subroutine test_three_centred

  !> Span 8 m, rise 2 m: every intrados joint on ((x - 4)/4)^2 + (y/2)^2 = 1 and on
  !> y = 4 r x (L - x) / L^2; the arcs between joints equal, measured by a polyline of
  !> 20000 pieces along each curve (independent of the builder's arc lengths).
  subroutine test_elliptical_and_parabolic()
    type(bridge_config_t) :: b
    real(dp) :: inner(2, 0:16), outer(2, 0:16), arcs(16)
    integer :: j
    b = one_span('elliptical', 8.0_dp, 2.0_dp, 0.4_dp, 16)
    call bridge_ring_joints(b, 1, inner, outer)
    do j = 0, 16
      call assert_close(((inner(1, j) - 4.0_dp)/4.0_dp)**2 + (inner(2, j)/2.0_dp)**2, 1.0_dp, &
                        'bridge: elliptical intrados on the ellipse', rtol=1.0e-12_dp)
    end do
    do j = 1, 16
      arcs(j) = ellipse_arc(atan2(inner(2, j - 1)/2.0_dp, (4.0_dp - inner(1, j - 1))/4.0_dp), &
                            atan2(inner(2, j)/2.0_dp, (4.0_dp - inner(1, j))/4.0_dp))
    end do
    call assert_true((maxval(arcs) - minval(arcs))/maxval(arcs) < 1.0e-7_dp, 'bridge: elliptical equal arcs')
    call assert_close(outer(2, 0), 0.0_dp, 'bridge: elliptical springing joint level', atol=1.0e-15_dp)
    b = one_span('parabolic', 8.0_dp, 2.0_dp, 0.4_dp, 16)
    call bridge_ring_joints(b, 1, inner, outer)
    do j = 0, 16
      call assert_close(inner(2, j), 0.125_dp*inner(1, j)*(8.0_dp - inner(1, j)), &
                        'bridge: parabolic intrados on y = 4 r x (L - x)/L^2', atol=1.0e-12_dp)
    end do
    do j = 1, 16
      arcs(j) = parabola_arc(inner(1, j - 1), inner(1, j))
    end do
    call assert_true((maxval(arcs) - minval(arcs))/maxval(arcs) < 1.0e-7_dp, 'bridge: parabolic equal arcs')
    ! The springing joint along the normal (-y'(0), 1) = (-1, 1)/sqrt 2.
    call assert_close(outer(1, 0), -0.4_dp/sqrt(2.0_dp), 'bridge: parabolic springing joint normal', rtol=1.0e-12_dp)
  end subroutine test_elliptical_and_parabolic

  !> Two segmental spans (10 m, rise 2.5 m) on a pier 1.5 m wide and 3 m high: 2 x 12
  !> voussoirs, the pier (free), two abutments and the ground (driven); the pier's top holds
  !> both springing joints as faces; each part its density and friction.
  subroutine test_two_spans_on_a_pier()
    type(bridge_config_t) :: b
    type(assembly_t) :: a
    type(status_t) :: status
    real(dp) :: inner(2, 0:12, 2), outer(2, 0:12, 2)
    b = one_span('segmental', 10.0_dp, 2.5_dp, 0.45_dp, 12)
    b%span_m(2) = 10.0_dp
    b%rise_m(2) = 2.5_dp
    b%n_spans = 2
    b%pier_width_m = 1.5_dp
    b%pier_height_m = 3.0_dp
    b%ring_friction = 0.7_dp
    b%pier_friction = 0.5_dp
    b%pier_density_kg_m3 = 2400.0_dp
    call build_bridge(b, a, status)
    call assert_true(status%ok .and. a%n_bodies == 24 + 1 + 2 + 1, 'bridge: two spans, a pier, abutments, ground')
    call assert_true(.not. a%driven(25) .and. all(a%driven(26:28)), 'bridge: the pier free, the rest driven')
    call assert_true(all(a%role(26:28) == role_foundation) .and. all(a%role(1:25) == role_voussoir), 'bridge: roles')
    call bridge_ring_joints(b, 1, inner(:, :, 1), outer(:, :, 1))
    call bridge_ring_joints(b, 2, inner(:, :, 2), outer(:, :, 2))
    call assert_close(inner(1, 0, 2), 11.5_dp, 'bridge: span 2 springs a pier width after span 1', rtol=1.0e-15_dp)
    call assert_true(has_vertex(a%polygon(25)%xy, inner(:, 12, 1)) .and. has_vertex(a%polygon(25)%xy, outer(:, 12, 1)) &
                     .and. has_vertex(a%polygon(25)%xy, inner(:, 0, 2)) .and. &
                     has_vertex(a%polygon(25)%xy, outer(:, 0, 2)), 'bridge: the pier carries both springing joints')
    call assert_close(minval(a%polygon(25)%xy(2, :)), -3.0_dp, 'bridge: pier height', rtol=1.0e-15_dp)
    call assert_true(all(a%friction(1:24) == 0.7_dp) .and. a%friction(25) == 0.5_dp .and. &
                     a%density_kg_m3(25) == 2400.0_dp .and. all(a%density_kg_m3(1:24) == 2000.0_dp), &
                     'bridge: each part its friction and density')
    call assert_true(a%block_name(1) == 'span 1 voussoir 1' .and. a%block_name(24) == 'span 2 voussoir 12' .and. &
                     a%block_name(25) == 'pier 1' .and. a%block_name(26) == 'left abutment' .and. &
                     a%block_name(27) == 'right abutment' .and. a%block_name(28) == 'ground', 'bridge: block names')
    call test_parts_in_the_kernel(a)
  end subroutine test_two_spans_on_a_pier

  !> The dynamics takes each part's density (the pier's mass 2400 kg/m3 x area x width, a
  !> voussoir's 2000) and friction (ring 0.7 and pier 0.5: their joint the lesser, 0.5; the
  !> ring's own joints 0.7; the pier on the ground 0.5), whatever the run's own values.
  subroutine test_parts_in_the_kernel(a)
    type(assembly_t), intent(in) :: a
    type(bodies_t) :: bodies
    type(contact_law_t) :: law
    type(status_t) :: status
    real(dp) :: no_joint(0:0)
    no_joint = -1.0_dp
    call bodies_init(a, 1.0_dp, 2.0_dp, bodies, status)
    call assert_true(status%ok, 'bridge: bodies of the kernel')
    call assert_close(bodies%mass_kg(25), 2400.0_dp*2.0_dp*polygon_area(a%polygon(25)%xy), 'bridge: pier mass', &
                      rtol=1.0e-14_dp)
    call assert_close(bodies%mass_kg(3), 2000.0_dp*2.0_dp*polygon_area(a%polygon(3)%xy), 'bridge: voussoir mass', &
                      rtol=1.0e-14_dp)
    call contact_law_init(0.9_dp, 0.0_dp, no_joint, a, law, status)
    call assert_true(status%ok .and. pair_friction_of(law, 12, 25) == 0.5_dp .and. &
                     pair_friction_of(law, 3, 4) == 0.7_dp .and. pair_friction_of(law, 25, 28) == 0.5_dp, &
                     'bridge: contact friction the lesser of the two parts')
  end subroutine test_parts_in_the_kernel

  logical function has_vertex(xy, p)
    real(dp), intent(in) :: xy(:, :), p(2)
    has_vertex = any(norm2(xy - spread(p, 2, size(xy, 2)), dim=1) < 1.0e-12_dp)
  end function has_vertex

  !> The circle through three points.
  subroutine circle_through(p1, p2, p3, centre, r)
    real(dp), intent(in) :: p1(2), p2(2), p3(2)
    real(dp), intent(out) :: centre(2), r
    real(dp) :: a(2, 2), rhs(2), det
    a(1, :) = 2.0_dp*(p2 - p1)
    a(2, :) = 2.0_dp*(p3 - p1)
    rhs = [dot_product(p2, p2) - dot_product(p1, p1), dot_product(p3, p3) - dot_product(p1, p1)]
    det = a(1, 1)*a(2, 2) - a(1, 2)*a(2, 1)
    centre = [rhs(1)*a(2, 2) - rhs(2)*a(1, 2), a(1, 1)*rhs(2) - a(2, 1)*rhs(1)]/det
    r = norm2(p1 - centre)
  end subroutine circle_through

  !> Length of the ellipse (4 (1 - cos), 2 sin)'s arc from parameter t0 to t1 (polyline).
  real(dp) function ellipse_arc(t0, t1)
    real(dp), intent(in) :: t0, t1
    integer, parameter :: m = 20000
    real(dp) :: t, prev(2), p(2)
    integer :: k
    ellipse_arc = 0.0_dp
    prev = [4.0_dp*(1.0_dp - cos(t0)), 2.0_dp*sin(t0)]
    do k = 1, m
      t = t0 + (t1 - t0)*k/m
      p = [4.0_dp*(1.0_dp - cos(t)), 2.0_dp*sin(t)]
      ellipse_arc = ellipse_arc + norm2(p - prev)
      prev = p
    end do
  end function ellipse_arc

  !> Length of the parabola y = x (8 - x)/8 from x0 to x1 (polyline).
  real(dp) function parabola_arc(x0, x1)
    real(dp), intent(in) :: x0, x1
    integer, parameter :: m = 20000
    real(dp) :: x, prev(2), p(2)
    integer :: k
    parabola_arc = 0.0_dp
    prev = [x0, 0.125_dp*x0*(8.0_dp - x0)]
    do k = 1, m
      x = x0 + (x1 - x0)*k/m
      p = [x, 0.125_dp*x*(8.0_dp - x)]
      parabola_arc = parabola_arc + norm2(p - prev)
      prev = p
    end do
  end function parabola_arc

end program test_bridge
