!> Assemblies of rigid polygons and the arch builder (polygon files: voussoir_polygon_file,
!> walls: voussoir_wall).
!>
!> An assembly is geometry only (vertices, which bodies are driven by the table, and for
!> arches the joint numbering of docs/measured_data.md); the dynamic state lives in
!> `bodies_t`.
module voussoir_assembly
  use voussoir_kinds, only: dp, pi
  use voussoir_random_stream, only: random_stream_t, stream_init, stream_uniform
  implicit none
  private

  public :: polygon_t, assembly_t, build_arch, arch_joint_angle_deg, voussoir_angle_factors, mirrored_blocks
  public :: between_rings
  public :: role_voussoir, role_foundation, role_restraint, role_fill, role_backing

  integer, parameter :: role_voussoir = 1    !! a free block of the arch
  integer, parameter :: role_foundation = 2  !! a block carried by the table
  integer, parameter :: role_restraint = 3   !! a bracket carried by the table
  integer, parameter :: role_fill = 4        !! a free particle of a bridge's fill (not watched for collapse)
  integer, parameter :: role_backing = 5     !! a free block of a bridge's backing (not watched for collapse)

  !> One convex polygon, vertices counter-clockwise, absolute coordinates [m].
  type :: polygon_t
    real(dp), allocatable :: xy(:, :)
  end type polygon_t

  !> Geometry of an assembly of blocks.
  type :: assembly_t
    integer :: n_bodies = 0
    type(polygon_t), allocatable :: polygon(:)
    logical, allocatable :: driven(:)       !! velocity imposed by the table
    integer, allocatable :: role(:)
    integer, allocatable :: course(:)       !! a wall's course of each body, 0 the foundation (else unallocated)
    !> Each body's own density [kg/m3] where allocated (the parts of a bridge), else the run's.
    real(dp), allocatable :: density_kg_m3(:)
    !> Each body's Coulomb coefficient where allocated (the parts of a bridge), else the
    !> run's; a contact between two bodies takes the lesser of theirs.
    real(dp), allocatable :: friction(:)
    !> Each body's compressive strength [Pa] where allocated (the parts of a bridge; 0: rigid,
    !> it does not crush); an interface takes the lesser of its two blocks' (a rigid block's
    !> neighbour's own).
    real(dp), allocatable :: compressive_strength_pa(:)
    !> A multi-ring bridge's ring of each body where allocated (1 the intrados ring, counted
    !> outwards; 0 no ring's): an interface between two rings takes ring_joint_friction
    !> instead of the lesser of its two blocks'.
    integer, allocatable :: ring(:)
    real(dp) :: ring_joint_friction = 0.0_dp
    !> Each body's name in the output where allocated (a bridge's: 'span 1 voussoir 3',
    !> 'pier 1', 'left abutment', 'ground'), else the body's number.
    character(len=32), allocatable :: block_name(:)
    !> A fill over the blocks (a bridge's, &bridge fill_density_kg_m3 > 0): its level
    !> surface [m], its weight per unit area of the section (density x g x width) [N/m2],
    !> and the angle from the vertical at which live loads spread through it [deg].
    logical :: has_fill = .false.
    real(dp) :: fill_level_m = 0.0_dp
    real(dp) :: fill_weight_n_m2 = 0.0_dp
    real(dp) :: dispersion_angle_deg = 0.0_dp
    !> Live loads spread instead by Flamant's vertical stress (Boussinesq's problem in plane
    !> strain) onto the blocks' top, truncated and scaled to the load (placed_loads).
    logical :: dispersion_boussinesq = .false.
    !> Its horizontal pressure on the top faces of free blocks, as a multiple of the vertical
    !> stress: at least `active_k`, at most `passive_k` (both 0: none).
    real(dp) :: fill_active_k = 0.0_dp
    real(dp) :: fill_passive_k = 0.0_dp
    ! Arch description (n_voussoirs = 0 for a generic assembly).
    integer :: n_voussoirs = 0
    real(dp) :: thickness_m = 0.0_dp
    real(dp) :: r_ext_m = 0.0_dp
    integer, allocatable :: joint_bodies(:, :)      !! (2, 0:n) bodies on each side of joint j
    real(dp), allocatable :: joint_intrados_xy(:, :) !! (2, 0:n) inner end of joint j [m]
    real(dp), allocatable :: joint_extrados_xy(:, :) !! (2, 0:n) outer end of joint j [m]
  end type assembly_t

contains

  !> The blocks of `asm` reflected in the plane x = 0 (each polygon's vertices reversed,
  !> so they stay counter-clockwise), with their driven flags and roles: what pushes the
  !> assembly towards +x pushes the original towards -x. The arch description is not
  !> carried (joint j of the mirror would be joint n - j).
  pure function mirrored_blocks(asm) result(mirror)
    type(assembly_t), intent(in) :: asm
    type(assembly_t) :: mirror
    integer :: b, nv
    mirror%n_bodies = asm%n_bodies
    allocate (mirror%polygon(asm%n_bodies))
    do b = 1, asm%n_bodies
      nv = size(asm%polygon(b)%xy, 2)
      mirror%polygon(b)%xy = asm%polygon(b)%xy(:, nv:1:-1)
      mirror%polygon(b)%xy(1, :) = -mirror%polygon(b)%xy(1, :)
    end do
    mirror%driven = asm%driven
    if (allocated(asm%role)) mirror%role = asm%role
    if (allocated(asm%course)) mirror%course = asm%course
    if (allocated(asm%density_kg_m3)) mirror%density_kg_m3 = asm%density_kg_m3
    if (allocated(asm%friction)) mirror%friction = asm%friction
    if (allocated(asm%compressive_strength_pa)) mirror%compressive_strength_pa = asm%compressive_strength_pa
    if (allocated(asm%block_name)) mirror%block_name = asm%block_name
    if (allocated(asm%ring)) mirror%ring = asm%ring
    mirror%ring_joint_friction = asm%ring_joint_friction
    mirror%has_fill = asm%has_fill
    mirror%fill_level_m = asm%fill_level_m
    mirror%fill_weight_n_m2 = asm%fill_weight_n_m2
    mirror%dispersion_angle_deg = asm%dispersion_angle_deg
    mirror%dispersion_boussinesq = asm%dispersion_boussinesq
    mirror%fill_active_k = asm%fill_active_k
    mirror%fill_passive_k = asm%fill_passive_k
  end function mirrored_blocks

  !> Whether bodies `a` and `b` of an assembly whose bodies lie in the rings `ring` (0: in
  !> none) belong to two different rings: their interface is a ring-to-ring joint.
  pure logical function between_rings(ring, a, b)
    integer, intent(in) :: ring(:), a, b
    between_rings = ring(a) > 0 .and. ring(b) > 0 .and. ring(a) /= ring(b)
  end function between_rings

  !> Angle [deg] from +x of the radial line of joint j (0..n) of an arch.
  pure real(dp) function arch_joint_angle_deg(embrace_deg, n_voussoirs, j)
    real(dp), intent(in) :: embrace_deg
    integer, intent(in) :: n_voussoirs, j
    arch_joint_angle_deg = 90.0_dp + 0.5_dp*embrace_deg - real(j, dp)*embrace_deg/real(n_voussoirs, dp)
  end function arch_joint_angle_deg

  !> Relative angles of the n voussoirs of an imperfect arch: 1 + `amplitude` (2 u - 1),
  !> u uniform from the stream `seed`, less their mean, so that they still fill the
  !> embrace (each differs from 1 by less than 2 `amplitude`); all 1 for amplitude 0.
  function voussoir_angle_factors(n_voussoirs, amplitude, seed) result(f)
    integer, intent(in) :: n_voussoirs, seed
    real(dp), intent(in) :: amplitude
    real(dp) :: f(n_voussoirs)
    type(random_stream_t) :: s
    real(dp) :: u
    integer :: i
    s = stream_init(seed)
    do i = 1, n_voussoirs
      call stream_uniform(s, u)
      f(i) = 2.0_dp*u - 1.0_dp
    end do
    f = 1.0_dp + amplitude*(f - sum(f)/n_voussoirs)
  end function voussoir_angle_factors

  !> The arch of docs/measured_data.md: n equal voussoirs with radial joints and chord
  !> faces, centre of the circle at the origin, on two foundation blocks whose top faces
  !> are the springing joints. Bodies 1..n are the voussoirs from left to right, n+1 the
  !> left foundation, n+2 the right one. With `restrained`, a bracket carried by the
  !> table stands against the outer face of the bottom voussoir on that side
  !> (restrained(1) left, restrained(2) right), `bracket_gap_m` off it (default 0: in
  !> contact). With `angle_factors` (n values of mean 1, see `voussoir_angle_factors`),
  !> voussoir i embraces angle_factors(i) embrace/n.
  subroutine build_arch(embrace_deg, n_voussoirs, r_ext_m, thickness_m, arch, restrained, angle_factors, &
                        bracket_gap_m)
    real(dp), intent(in) :: embrace_deg, r_ext_m, thickness_m
    integer, intent(in) :: n_voussoirs
    type(assembly_t), intent(out) :: arch
    logical, intent(in), optional :: restrained(2)
    real(dp), intent(in), optional :: angle_factors(n_voussoirs)
    real(dp), intent(in), optional :: bracket_gap_m
    real(dp) :: r_int, ang, inner(2, 0:n_voussoirs), outer(2, 0:n_voussoirs), swept, gap
    logical :: bracket(2)
    integer :: j, n, nb, side

    n = n_voussoirs
    gap = 0.0_dp
    if (present(bracket_gap_m)) gap = bracket_gap_m
    bracket = .false.
    if (present(restrained)) bracket = restrained
    nb = n + 2 + count(bracket)
    r_int = r_ext_m - thickness_m
    swept = 0.0_dp
    do j = 0, n
      ang = arch_joint_angle_deg(embrace_deg, n, j)*pi/180.0_dp
      if (present(angle_factors)) then
        ! The springings stay where they are; the joints between move.
        if (j > 0) swept = swept + angle_factors(j)
        if (j > 0 .and. j < n) ang = (90.0_dp + 0.5_dp*embrace_deg - swept*embrace_deg/n)*pi/180.0_dp
      end if
      inner(:, j) = r_int*[cos(ang), sin(ang)]
      outer(:, j) = r_ext_m*[cos(ang), sin(ang)]
    end do

    arch%n_bodies = nb
    arch%n_voussoirs = n
    arch%thickness_m = thickness_m
    arch%r_ext_m = r_ext_m
    allocate (arch%polygon(nb), arch%driven(nb), arch%role(nb))
    allocate (arch%joint_bodies(2, 0:n), arch%joint_intrados_xy(2, 0:n), arch%joint_extrados_xy(2, 0:n))
    arch%joint_intrados_xy = inner
    arch%joint_extrados_xy = outer

    do j = 1, n
      ! Counter-clockwise: inner left, inner right, outer right, outer left.
      arch%polygon(j)%xy = reshape([inner(:, j - 1), inner(:, j), outer(:, j), outer(:, j - 1)], [2, 4])
      arch%driven(j) = .false.
      arch%role(j) = role_voussoir
      arch%joint_bodies(:, j) = [j, j + 1]
    end do
    arch%joint_bodies(:, 0) = [n + 1, 1]
    arch%joint_bodies(:, n) = [n, n + 2]

    ! Foundations: the springing joint on top, vertical sides, flat bottom a thickness
    ! below the lower end of the joint.
    arch%polygon(n + 1)%xy = foundation(outer(:, 0), inner(:, 0), thickness_m)
    arch%polygon(n + 2)%xy = foundation(inner(:, n), outer(:, n), thickness_m)
    arch%driven(n + 1:n + 2) = .true.
    arch%role(n + 1:n + 2) = role_foundation

    j = n + 2
    do side = 1, 2
      if (.not. bracket(side)) cycle
      j = j + 1
      arch%polygon(j)%xy = bracket_block(side, outer, n, thickness_m, gap)
      arch%driven(j) = .true.
      arch%role(j) = role_restraint
    end do
  end subroutine build_arch

  !> Foundation under the springing joint from `left_top` to `right_top`.
  pure function foundation(left_top, right_top, depth_m) result(xy)
    real(dp), intent(in) :: left_top(2), right_top(2), depth_m
    real(dp) :: xy(2, 4), y_bottom
    y_bottom = min(left_top(2), right_top(2)) - depth_m
    xy(:, 1) = [left_top(1), y_bottom]
    xy(:, 2) = [right_top(1), y_bottom]
    xy(:, 3) = right_top
    xy(:, 4) = left_top
  end function foundation

  !> A bracket on the table against the outer (extrados) face of the bottom voussoir of
  !> `side` (1 left, 2 right): its inner face is the lower half of that extrados chord,
  !> it is a thickness wide and stands on the level of the springing's outer corner.
  !> With a gap, the whole block stands that far off the chord, along the chord's
  !> outward normal (the radius through the chord's middle): a bracket with play.
  pure function bracket_block(side, outer, n, thickness_m, gap_m) result(xy)
    integer, intent(in) :: side, n
    real(dp), intent(in) :: outer(2, 0:n), thickness_m, gap_m
    real(dp) :: xy(2, 4), p0(2), mid(2), normal(2)
    integer :: k
    if (side == 1) then
      p0 = outer(:, 0)
      mid = 0.5_dp*(p0 + outer(:, 1))
      xy = reshape([[p0(1) - thickness_m, p0(2)], p0, mid, [p0(1) - thickness_m, mid(2)]], [2, 4])
    else
      p0 = outer(:, n)
      mid = 0.5_dp*(p0 + outer(:, n - 1))
      xy = reshape([p0, [p0(1) + thickness_m, p0(2)], [p0(1) + thickness_m, mid(2)], mid], [2, 4])
    end if
    normal = mid/norm2(mid)   ! mid is the middle of the chord, the circle's centre the origin
    do k = 1, 4
      xy(:, k) = xy(:, k) + gap_m*normal
    end do
  end function bracket_block

end module voussoir_assembly
