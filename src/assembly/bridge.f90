!> Masonry arch bridges: the assembly that a &bridge group (voussoir_bridge_config)
!> describes, the same blocks the kernel and the limit analysis take from the arch builder
!> or a polygon file. docs/bridges.md.
!>
!> Frame: x = 0 at the left intrados springing of span 1, y = 0 at the springings, the
!> spans one after another with a pier between each two. Bodies, in order: the voussoirs
!> of span 1 from the left (ring by ring from the intrados with n_rings > 1), then of span
!> 2, ...; the piers (free blocks) from the left; the left and the right abutment (driven);
!> with piers, the ground under them (driven). Each voussoir is the quadrilateral of its
!> two joints (chord faces), a joint running from the intrados along its normal to a
!> ring_thickness_m deep extrados point; the joints divide the intrados into n_voussoirs
!> equal arc lengths. With n_rings > 1 every joint is cut at n_rings - 1 equally spaced
!> points between, the same for all rings: a voussoir's extrados chord is the next ring's
!> voussoir's intrados chord, point for point (the interface between the rings). Staggered
!> joints would not do: a voussoir bridging a joint of the ring beneath would rest on two
!> chords at an angle, a non-convex face. Each block carries its part's density and
!> friction (an interface takes the lesser friction of its two blocks; between two rings,
!> ring_joint_friction).
!> With fill_model = 'particles' the fill's particles follow (free). No wall retains them at
!> the abutments' backs: between two fixed walls the fill, rigid blocks with associative
!> friction and no crushing, is a flat arch whose thrust the walls take without bound, and
!> the LP finds no collapse (measured: unbounded); the fill ends in free faces there.
module voussoir_bridge
  use voussoir_kinds, only: dp, g_m_s2, pi
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa
  use voussoir_geometry, only: is_convex_ccw
  use voussoir_assembly, only: assembly_t, polygon_t, role_voussoir, role_foundation, role_fill, role_backing
  use voussoir_bridge_shape, only: intrados_t, intrados_at, crown_extrados_m, shape_pointed
  use voussoir_bridge_config, only: bridge_config_t, bridge_intrados, fill_model_particles, dispersion_boussinesq
  use voussoir_wall, only: box
  use voussoir_fill_particles, only: cut_fill_particles
  use voussoir_bridge_backing, only: cut_backing
  implicit none
  private
  public :: build_bridge, bridge_span_left_x, bridge_ring_joints, bridge_joint_levels

contains

  !> The x of span k's left intrados springing [m].
  pure real(dp) function bridge_span_left_x(b, k)
    type(bridge_config_t), intent(in) :: b
    integer, intent(in) :: k
    bridge_span_left_x = sum(b%span_m(1:k - 1)) + (k - 1)*b%pier_width_m
  end function bridge_span_left_x

  !> The joints 0..n of span k's ring: their intrados and extrados ends [m], in the bridge's
  !> frame (bridge_joint_levels' first and last levels).
  pure subroutine bridge_ring_joints(b, k, inner, outer)
    type(bridge_config_t), intent(in) :: b
    integer, intent(in) :: k
    real(dp), intent(out) :: inner(2, 0:b%n_voussoirs), outer(2, 0:b%n_voussoirs)
    real(dp) :: level(2, 0:b%n_voussoirs, 0:b%n_rings)
    call bridge_joint_levels(b, k, level)
    inner = level(:, :, 0)
    outer = level(:, :, b%n_rings)
  end subroutine bridge_ring_joints

  !> The points of the joints 0..n of span k [m], in the bridge's frame, at the depths
  !> m ring_thickness_m / n_rings, m = 0 (the intrados) .. n_rings (the extrados): ring r
  !> lies between levels r - 1 and r. The springings stand exactly at y = 0; the apex joint
  !> of a pointed arch is vertical, each level's point where the two arcs of that depth meet.
  pure subroutine bridge_joint_levels(b, k, level)
    type(bridge_config_t), intent(in) :: b
    integer, intent(in) :: k
    real(dp), intent(out) :: level(2, 0:b%n_voussoirs, 0:b%n_rings)
    type(intrados_t) :: c
    real(dp) :: x0, p(2), nrm(2), depth
    integer :: j, n, m
    c = bridge_intrados(b, k)
    n = b%n_voussoirs
    x0 = bridge_span_left_x(b, k)
    do j = 0, n
      ! s at j = n exactly the whole length (no round-off past the springing)
      call intrados_at(c, merge(c%length_m, c%length_m*j/n, j == n), p, nrm)
      if (j == 0) p = [0.0_dp, 0.0_dp]
      if (j == n) p = [b%span_m(k), 0.0_dp]
      level(:, j, 0) = [x0 + p(1), p(2)]
      do m = 1, b%n_rings
        depth = b%ring_thickness_m*m/b%n_rings
        level(:, j, m) = level(:, j, 0) + depth*nrm
        if (c%shape == shape_pointed .and. 2*j == n) level(:, j, m) = [x0 + 0.5_dp*b%span_m(k), crown_extrados_m(c, depth)]
        ! A springing joint normal to a vertical intrados is level (cos(pi/2) is not 0 in floating point).
        if ((j == 0 .or. j == n) .and. abs(level(2, j, m)) <= 1.0e-12_dp*depth) level(2, j, m) = 0.0_dp
      end do
    end do
  end subroutine bridge_joint_levels

  !> The blocks of the bridge `b` (validated by read_bridge_config); a block that comes
  !> out not convex fails `status` (a fault of the program: the checks of the group
  !> exclude it).
  subroutine build_bridge(b, asm, status)
    type(bridge_config_t), intent(in) :: b
    type(assembly_t), intent(out) :: asm
    type(status_t), intent(inout) :: status
    real(dp), allocatable :: inner(:, :, :), outer(:, :, :), level(:, :, :)
    type(polygon_t), allocatable :: particles(:), backing(:)
    real(dp) :: h, x_end, w
    integer :: n, ns, nr, nb, k, j, r, body
    logical :: with_particles

    n = b%n_voussoirs
    ns = b%n_spans
    nr = b%n_rings
    h = b%pier_height_m
    w = b%abutment_width_m
    with_particles = b%fill_model == fill_model_particles .and. b%fill_density_kg_m3 > 0.0_dp
    allocate (particles(0))
    if (with_particles) particles = cut_fill_particles(bridge_fill_bottom(b), b%fill_level_m, b%fill_particle_size_m)
    allocate (backing(0))
    if (b%backing_level_m > 0.0_dp) backing = cut_backing(bridge_fill_bottom(b), b%backing_level_m, b%backing_course_m)
    nb = ns*n*nr + (ns - 1) + 2 + merge(1, 0, ns > 1) + size(particles) + size(backing)
    allocate (asm%polygon(nb), asm%driven(nb), asm%role(nb), asm%density_kg_m3(nb), asm%friction(nb), &
              asm%block_name(nb))
    allocate (inner(2, 0:n, ns), outer(2, 0:n, ns), level(2, 0:n, 0:nr))
    asm%n_bodies = nb
    if (nr > 1) then   ! (a single ring: no ring-to-ring joints, the assembly as before rings)
      allocate (asm%ring(nb), source=0)
      asm%ring_joint_friction = b%ring_joint_friction
    end if
    asm%thickness_m = b%ring_thickness_m
    ! The particles are blocks: no columns, spread or pressure of the engineers' model.
    asm%has_fill = b%fill_density_kg_m3 > 0.0_dp .and. .not. with_particles
    asm%fill_level_m = b%fill_level_m
    asm%fill_weight_n_m2 = b%fill_density_kg_m3*g_m_s2*b%width_m
    asm%dispersion_angle_deg = b%dispersion_angle_deg
    asm%dispersion_boussinesq = b%dispersion == dispersion_boussinesq
    if (b%fill_friction_deg > 0.0_dp) then   ! Rankine's coefficients
      asm%fill_active_k = tan(0.25_dp*pi - 0.5_dp*b%fill_friction_deg*pi/180.0_dp)**2
      asm%fill_passive_k = max(asm%fill_active_k, &
                               b%passive_mobilisation*tan(0.25_dp*pi + 0.5_dp*b%fill_friction_deg*pi/180.0_dp)**2)
    end if
    body = 0
    do k = 1, ns
      call bridge_joint_levels(b, k, level)
      inner(:, :, k) = level(:, :, 0)
      outer(:, :, k) = level(:, :, nr)
      do r = 1, nr
        do j = 1, n
          ! Counter-clockwise: inner left, inner right, outer right, outer left.
          call add(reshape([level(:, j - 1, r - 1), level(:, j, r - 1), level(:, j, r), level(:, j - 1, r)], [2, 4]), &
                   .false., role_voussoir, b%ring_density_kg_m3, b%ring_friction, voussoir_name(k, r, j, nr))
          if (nr > 1 .and. status%ok) asm%ring(body) = r
        end do
      end do
    end do
    do k = 1, ns - 1
      call add(pier(inner(:, n, k), outer(:, n, k), inner(:, 0, k + 1), outer(:, 0, k + 1), h), .false., &
               role_voussoir, b%pier_density_kg_m3, b%pier_friction, 'pier '//itoa(k))
    end do
    ! The abutments: the springing joint on top, back to abutment_width_m, down to the ground.
    call add(left_abutment(outer(:, 0, 1), w, h), .true., role_foundation, b%pier_density_kg_m3, b%abutment_friction, &
             'left abutment')
    x_end = bridge_span_left_x(b, ns) + b%span_m(ns)
    call add(right_abutment(x_end, outer(:, n, ns), w, h), .true., role_foundation, b%pier_density_kg_m3, &
             b%abutment_friction, 'right abutment')
    if (ns > 1) call add(box(-w, x_end + w, -h - b%ring_thickness_m, -h), .true., role_foundation, &
                         b%pier_density_kg_m3, b%pier_friction, 'ground')
    do k = 1, size(backing)
      call add(backing(k)%xy, .false., role_backing, b%backing_density_kg_m3, b%backing_friction, 'backing '//itoa(k))
    end do
    if (with_particles) then
      do k = 1, size(particles)
        call add(particles(k)%xy, .false., role_fill, b%fill_density_kg_m3, b%fill_particle_friction, &
                 'fill particle '//itoa(k))
      end do
    end if
    call part_strengths(b, asm)

  contains

    subroutine add(xy, driven, role, density_kg_m3, friction, name)
      real(dp), intent(in) :: xy(:, :), density_kg_m3, friction
      logical, intent(in) :: driven
      integer, intent(in) :: role
      character(len=*), intent(in) :: name
      if (.not. status%ok) return
      body = body + 1
      if (.not. is_convex_ccw(xy)) then
        call fail(status, '&bridge: block '//itoa(body)//' of the bridge is not convex (a fault of the program)')
        return
      end if
      asm%polygon(body) = polygon_t(xy)
      asm%driven(body) = driven
      asm%role(body) = role
      asm%density_kg_m3(body) = density_kg_m3
      asm%friction(body) = friction
      asm%block_name(body) = name
    end subroutine add

  end subroutine build_bridge

  !> Voussoir j of ring r of span k: 'span k voussoir j', with `n_rings` > 1
  !> 'span k ring r voussoir j'.
  function voussoir_name(k, r, j, n_rings) result(name)
    integer, intent(in) :: k, r, j, n_rings
    character(len=:), allocatable :: name
    name = 'span '//itoa(k)//' voussoir '//itoa(j)
    if (n_rings > 1) name = 'span '//itoa(k)//' ring '//itoa(r)//' voussoir '//itoa(j)
  end function voussoir_name

  !> The parts' compressive strengths [Pa] on the blocks of `asm` built from `b` (0: rigid),
  !> for the LP's crushing: the ring's voussoirs ('span ...'), the piers, the backing; left
  !> unallocated where no part has one.
  subroutine part_strengths(b, asm)
    type(bridge_config_t), intent(in) :: b
    type(assembly_t), intent(inout) :: asm
    integer :: k
    if (b%ring_compressive_strength_pa <= 0.0_dp .and. b%pier_compressive_strength_pa <= 0.0_dp .and. &
        b%backing_compressive_strength_pa <= 0.0_dp) return
    allocate (asm%compressive_strength_pa(asm%n_bodies))
    asm%compressive_strength_pa = 0.0_dp
    do k = 1, asm%n_bodies
      if (asm%role(k) == role_backing) then
        asm%compressive_strength_pa(k) = b%backing_compressive_strength_pa
      else if (asm%block_name(k)(1:5) == 'span ') then
        asm%compressive_strength_pa(k) = b%ring_compressive_strength_pa
      else if (asm%block_name(k)(1:5) == 'pier ') then
        asm%compressive_strength_pa(k) = b%pier_compressive_strength_pa
      end if
    end do
  end subroutine part_strengths

  !> The bottom of the fill (2, n) [m], x ascending: the left abutment's level top from its
  !> back, the extrados ends of every span's joints from the left (across each pier's top
  !> from one span's last to the next one's first), the right abutment's top to its back.
  pure function bridge_fill_bottom(b) result(bottom)
    type(bridge_config_t), intent(in) :: b
    real(dp), allocatable :: bottom(:, :)
    real(dp) :: inner(2, 0:b%n_voussoirs), outer(2, 0:b%n_voussoirs), x_end
    integer :: k
    allocate (bottom(2, 0))
    do k = 1, b%n_spans
      call bridge_ring_joints(b, k, inner, outer)
      if (k == 1) bottom = reshape([-b%abutment_width_m, outer(2, 0)], [2, 1])
      bottom = reshape([bottom, outer], [2, size(bottom, 2) + b%n_voussoirs + 1])
    end do
    x_end = bridge_span_left_x(b, b%n_spans) + b%span_m(b%n_spans)
    bottom = reshape([bottom, x_end + b%abutment_width_m, bottom(2, size(bottom, 2))], [2, size(bottom, 2) + 1])
  end function bridge_fill_bottom

  !> A pier between a span's right springing joint (`in1` to `out1`) and the next span's
  !> left one (`in2` to `out2`), down to the ground `height_m` below the springings. A
  !> horizontal springing joint lies along the pier's flat top; inclined ones are its
  !> sloping faces, a flat between them where they do not meet.
  pure function pier(in1, out1, in2, out2, height_m) result(xy)
    real(dp), intent(in) :: in1(2), out1(2), in2(2), out2(2), height_m
    real(dp), allocatable :: xy(:, :)
    xy = reshape([in1(1), -height_m, in2(1), -height_m, in2(1), 0.0_dp], [2, 3])
    if (out2(2) > 0.0_dp) xy = reshape([xy, out2], [2, size(xy, 2) + 1])
    if (out1(2) > 0.0_dp .and. norm2(out1 - out2) > 1.0e-9_dp*height_m) xy = reshape([xy, out1], [2, size(xy, 2) + 1])
    xy = reshape([xy, in1(1), 0.0_dp], [2, size(xy, 2) + 1])
  end function pier

  !> The left abutment: its top the springing joint (from (0, 0) to `out`) and a level back
  !> to x = -width_m, its foot `height_m` below the springings.
  pure function left_abutment(out, width_m, height_m) result(xy)
    real(dp), intent(in) :: out(2), width_m, height_m
    real(dp), allocatable :: xy(:, :)
    if (out(2) > 0.0_dp) then
      xy = reshape([-width_m, -height_m, 0.0_dp, -height_m, 0.0_dp, 0.0_dp, out(1), out(2), -width_m, out(2)], [2, 5])
    else
      xy = box(-width_m, 0.0_dp, -height_m, 0.0_dp)
    end if
  end function left_abutment

  !> The right abutment, the mirror of the left one about the last span's right springing
  !> at x = `x_end`.
  pure function right_abutment(x_end, out, width_m, height_m) result(xy)
    real(dp), intent(in) :: x_end, out(2), width_m, height_m
    real(dp), allocatable :: xy(:, :)
    if (out(2) > 0.0_dp) then
      xy = reshape([x_end, -height_m, x_end + width_m, -height_m, x_end + width_m, out(2), out(1), out(2), &
                    x_end, 0.0_dp], [2, 5])
    else
      xy = box(x_end, x_end + width_m, -height_m, 0.0_dp)
    end if
  end function right_abutment

end module voussoir_bridge
