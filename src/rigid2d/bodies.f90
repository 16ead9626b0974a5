!> Rigid polygonal bodies: mass properties, state (x, y, rotation) and their velocities.
module voussoir_bodies
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_geometry, only: polygon_area, polygon_centroid, polygon_polar_moment
  use voussoir_assembly, only: assembly_t
  implicit none
  private

  public :: bodies_t, bodies_init, update_world_vertices, add_point_load, external_load, add_carried_mass

  !> All bodies of a model, structure of arrays. Index 1 of the state is x [m], 2 is
  !> y [m], 3 is the rotation [rad] from the reference configuration.
  type :: bodies_t
    integer :: n = 0
    integer :: max_vertices = 0
    real(dp), allocatable :: q(:, :)        !! (3, n) centre of mass and rotation (the polygon's centroid
                                            !! unless the body carries a mass: add_carried_mass)
    real(dp), allocatable :: q_ref(:, :)    !! (3, n) reference configuration
    real(dp), allocatable :: v(:, :)        !! (3, n) velocity [m/s, m/s, rad/s]
    real(dp), allocatable :: mass_kg(:)
    real(dp), allocatable :: inertia_kg_m2(:)
    real(dp), allocatable :: inv_mass(:)    !! 0 for driven bodies
    real(dp), allocatable :: inv_inertia(:) !! 0 for driven bodies
    logical, allocatable :: driven(:)
    integer, allocatable :: role(:)
    integer, allocatable :: n_vertices(:)
    real(dp), allocatable :: vertex_local(:, :, :) !! (2, max_vertices, n) about the centroid
    real(dp), allocatable :: vertex(:, :, :)       !! (2, max_vertices, n) world, current
    real(dp), allocatable :: face_normal_local(:, :, :) !! (2, max_vertices, n) outward, reference
    real(dp), allocatable :: face_normal(:, :, :)       !! (2, max_vertices, n) outward, current
    real(dp), allocatable :: radius_m(:)           !! farthest vertex from the centroid
    ! Constant forces at material points (the loads of &load), summed per body:
    real(dp), allocatable :: ext_force_n(:, :)     !! (2, n) their resultant [N], fixed in direction
    real(dp), allocatable :: ext_cross_nm(:)       !! sum of r x F, r from the centroid in the reference [N m]
    real(dp), allocatable :: ext_dot_nm(:)         !! sum of r . F [N m]: the moment turns with the body
    logical :: has_external = .false.              !! any body has one (else the step skips them)
  end type bodies_t

contains

  !> Mass properties of every polygon of `assembly` for a density [kg/m3] and an
  !> out-of-plane width [m]; driven bodies get zero inverse mass and inertia.
  subroutine bodies_init(assembly, density_kg_m3, width_m, bodies, status)
    type(assembly_t), intent(in) :: assembly
    real(dp), intent(in) :: density_kg_m3, width_m
    type(bodies_t), intent(out) :: bodies
    type(status_t), intent(inout) :: status
    integer :: i, nv, n, k
    real(dp) :: area, c(2), e(2), rho

    n = assembly%n_bodies
    bodies%n = n
    bodies%max_vertices = 0
    do i = 1, n
      bodies%max_vertices = max(bodies%max_vertices, size(assembly%polygon(i)%xy, 2))
    end do
    allocate (bodies%q(3, n), bodies%q_ref(3, n), bodies%v(3, n), bodies%mass_kg(n), &
              bodies%inertia_kg_m2(n), bodies%inv_mass(n), bodies%inv_inertia(n), &
              bodies%driven(n), bodies%role(n), bodies%n_vertices(n), &
              bodies%vertex_local(2, bodies%max_vertices, n), &
              bodies%vertex(2, bodies%max_vertices, n), bodies%radius_m(n), &
              bodies%face_normal_local(2, bodies%max_vertices, n), &
              bodies%face_normal(2, bodies%max_vertices, n), bodies%ext_force_n(2, n), &
              bodies%ext_cross_nm(n), bodies%ext_dot_nm(n))
    bodies%ext_force_n = 0.0_dp
    bodies%ext_cross_nm = 0.0_dp
    bodies%ext_dot_nm = 0.0_dp
    bodies%face_normal_local = 0.0_dp
    bodies%vertex_local = 0.0_dp
    bodies%v = 0.0_dp
    do i = 1, n
      associate (xy => assembly%polygon(i)%xy)
        nv = size(xy, 2)
        area = polygon_area(xy)
        if (area <= 0.0_dp) then
          call fail(status, 'body has zero or negative area (vertices must be counter-clockwise)')
          return
        end if
        c = polygon_centroid(xy)
        bodies%n_vertices(i) = nv
        bodies%vertex_local(:, 1:nv, i) = xy - spread(c, 2, nv)
        bodies%radius_m(i) = maxval(norm2(bodies%vertex_local(:, 1:nv, i), dim=1))
        do k = 1, nv
          e = xy(:, modulo(k, nv) + 1) - xy(:, k)
          bodies%face_normal_local(:, k, i) = [e(2), -e(1)]/norm2(e)
        end do
        bodies%q(:, i) = [c(1), c(2), 0.0_dp]
        rho = density_kg_m3
        if (allocated(assembly%density_kg_m3)) rho = assembly%density_kg_m3(i)   ! a bridge's parts
        bodies%mass_kg(i) = rho*width_m*area
        bodies%inertia_kg_m2(i) = rho*width_m*polygon_polar_moment(xy)
      end associate
    end do
    bodies%q_ref = bodies%q
    bodies%driven = assembly%driven
    bodies%role = assembly%role
    where (bodies%driven)
      bodies%inv_mass = 0.0_dp
      bodies%inv_inertia = 0.0_dp
    elsewhere
      bodies%inv_mass = 1.0_dp/bodies%mass_kg
      bodies%inv_inertia = 1.0_dp/bodies%inertia_kg_m2
    end where
    call update_world_vertices(bodies, bodies%q)
  end subroutine bodies_init

  !> Body i carries a mass `mass_kg` [kg] that moves with it (a bridge's fill over a
  !> voussoir), its centre of mass at `centroid_xy` [m] in the reference configuration and
  !> its moment of inertia `inertia_kg_m2` about that centre. The body becomes the composite
  !> of the two: mass m_b + m_c, centre of mass (m_b c_b + m_c c_c)/(m_b + m_c), inertia
  !> about it by parallel axes from both centres. Its reference point moves to the new
  !> centre of mass (the vertices are kept where they are), so gravity on the whole mass
  !> and a table's inertial load act there; the constant loads already on it keep their
  !> points (their moments are moved to the new reference point).
  pure subroutine add_carried_mass(bodies, i, mass_kg, centroid_xy, inertia_kg_m2)
    type(bodies_t), intent(inout) :: bodies
    integer, intent(in) :: i
    real(dp), intent(in) :: mass_kg, centroid_xy(2), inertia_kg_m2
    real(dp) :: m_total, c_old(2), c_new(2), shift(2)
    integer :: nv, k
    if (.not. mass_kg > 0.0_dp) return
    c_old = bodies%q_ref(1:2, i)
    m_total = bodies%mass_kg(i) + mass_kg
    c_new = (bodies%mass_kg(i)*c_old + mass_kg*centroid_xy)/m_total
    bodies%inertia_kg_m2(i) = bodies%inertia_kg_m2(i) + bodies%mass_kg(i)*sum((c_old - c_new)**2) &
                              + inertia_kg_m2 + mass_kg*sum((centroid_xy - c_new)**2)
    bodies%mass_kg(i) = m_total
    shift = c_old - c_new
    nv = bodies%n_vertices(i)
    do k = 1, nv
      bodies%vertex_local(:, k, i) = bodies%vertex_local(:, k, i) + shift
    end do
    bodies%radius_m(i) = maxval(norm2(bodies%vertex_local(:, 1:nv, i), dim=1))
    ! r' = r + shift for every load's point r from the old reference point.
    associate (f => bodies%ext_force_n(:, i))
      bodies%ext_cross_nm(i) = bodies%ext_cross_nm(i) + (shift(1)*f(2) - shift(2)*f(1))
      bodies%ext_dot_nm(i) = bodies%ext_dot_nm(i) + dot_product(shift, f)
    end associate
    bodies%q_ref(1:2, i) = c_new
    bodies%q(1:2, i) = bodies%q(1:2, i) - shift
    if (.not. bodies%driven(i)) then
      bodies%inv_mass(i) = 1.0_dp/bodies%mass_kg(i)
      bodies%inv_inertia(i) = 1.0_dp/bodies%inertia_kg_m2(i)
    end if
    call update_world_vertices(bodies, bodies%q)
  end subroutine add_carried_mass

  !> Add a constant force `force_n` [N] acting at the material point that is at `xy_m` [m]
  !> in the reference configuration of body i.
  pure subroutine add_point_load(bodies, i, xy_m, force_n)
    type(bodies_t), intent(inout) :: bodies
    integer, intent(in) :: i
    real(dp), intent(in) :: xy_m(2), force_n(2)
    real(dp) :: r(2)
    r = xy_m - bodies%q_ref(1:2, i)
    bodies%has_external = .true.
    bodies%ext_force_n(:, i) = bodies%ext_force_n(:, i) + force_n
    bodies%ext_cross_nm(i) = bodies%ext_cross_nm(i) + (r(1)*force_n(2) - r(2)*force_n(1))
    bodies%ext_dot_nm(i) = bodies%ext_dot_nm(i) + dot_product(r, force_n)
  end subroutine add_point_load

  !> The external force and moment (fx, fy [N], m [N m]) on body i turned by `angle_rad`
  !> from its reference: the points turn with the body, the forces keep their direction,
  !> so the moment is sum((R r) x F) = cos(angle) sum(r x F) - sin(angle) sum(r . F).
  pure function external_load(bodies, i, angle_rad) result(f)
    type(bodies_t), intent(in) :: bodies
    integer, intent(in) :: i
    real(dp), intent(in) :: angle_rad
    real(dp) :: f(3)
    f = 0.0_dp
    if (.not. bodies%has_external) return
    f = [bodies%ext_force_n(:, i), cos(angle_rad)*bodies%ext_cross_nm(i) - sin(angle_rad)*bodies%ext_dot_nm(i)]
  end function external_load

  !> World coordinates of every vertex and face normal for the configuration `q` (3, n).
  pure subroutine update_world_vertices(bodies, q)
    type(bodies_t), intent(inout) :: bodies
    real(dp), intent(in) :: q(:, :)
    integer :: i, k
    real(dp) :: c, s
    do i = 1, bodies%n
      c = cos(q(3, i))
      s = sin(q(3, i))
      do k = 1, bodies%n_vertices(i)
        associate (p => bodies%vertex_local(:, k, i))
          bodies%vertex(1, k, i) = q(1, i) + c*p(1) - s*p(2)
          bodies%vertex(2, k, i) = q(2, i) + s*p(1) + c*p(2)
        end associate
        associate (p => bodies%face_normal_local(:, k, i))
          bodies%face_normal(1, k, i) = c*p(1) - s*p(2)
          bodies%face_normal(2, k, i) = s*p(1) + c*p(2)
        end associate
      end do
    end do
  end subroutine update_world_vertices

end module voussoir_bodies
