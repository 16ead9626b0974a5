!> Limit analysis of a chain of rigid blocks (Heyman: rigid, no tension, no sliding).
!>
!> A chain is n blocks joined end to end: block i lies between joint i-1 and joint i,
!> each joint is a segment from its intrados end point to its extrados end point. In an
!> arch (`free_top = .false.`) both end joints bear on driven supports; in a stack
!> (`free_top = .true.`) joint 0 bears on the support and joint n carries nothing.
!>
!> Kinematic side: a hinge pivots on one end point of a joint (set in along the joint by
!> the inset); it is admissible when the joint opens, i.e. the other end separates. The
!> horizontal collapse multiplier (acceleration / g) of a uniform body force
!> lambda * weight is the minimum, over all admissible one-degree-of-freedom mechanisms
!> (four hinges for an arch, one for a stack), of the ratio of the power of the weights
!> to that of the horizontal load, evaluated in closed form from instantaneous centres.
!> Static side: the line of thrust through the hinges of the minimising mechanism is
!> checked against every joint; where it stays inside, the lower and upper bounds meet.
!> The shear-to-normal ratio of every joint resultant of that solution is compared with
!> the friction coefficient: this checks the hinging solution, it is not a limit
!> analysis with sliding.
module voussoir_limit_analysis
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_geometry, only: polygon_area, polygon_centroid, cross2
  use voussoir_assembly, only: assembly_t, build_arch, role_restraint
  use voussoir_hinge_side, only: side_intrados, side_extrados
  implicit none
  private

  public :: block_chain_t, limit_result_t
  public :: arch_chain, chain_capacity, horizontal_capacity


  !> Allowed excursion of the thrust outside a joint, as a fraction of its length.
  real(dp), parameter :: thrust_rel_tol = 1.0e-9_dp
  !> Allowed difference of the static and kinematic multipliers (multiplier units).
  real(dp), parameter :: lambda_tol = 1.0e-9_dp
  !> Relative size below which a determinant or a power counts as zero.
  real(dp), parameter :: degenerate_rel_tol = 1.0e-12_dp

  !> A chain of rigid blocks: block i (1..n) lies between joint i-1 and joint i.
  !> Arrays are read by position (the first joint column is joint 0, whatever its index).
  type :: block_chain_t
    integer :: n_blocks = 0
    real(dp), allocatable :: weight(:)                !! (n) weight of each block (e.g. area [m2])
    real(dp), allocatable :: centroid_xy(:, :)        !! (2, n) centre of gravity of each block [m]
    real(dp), allocatable :: joint_intrados_xy(:, :)  !! (2, 0:n) intrados end of joint j [m]
    real(dp), allocatable :: joint_extrados_xy(:, :)  !! (2, 0:n) extrados end of joint j [m]
    !> Joint n carries nothing (a stack on a base) instead of bearing on a support.
    logical :: free_top = .false.
  end type block_chain_t

  !> Horizontal collapse multipliers of a chain, with their mechanisms and checks.
  !>
  !> `pos` refers to the body force towards +x, `neg` towards -x; both multipliers are
  !> magnitudes (collapse acceleration / g) and are negative when the chain cannot carry
  !> its own weight. Hinges are joint indices (0..n) with sides `side_intrados` /
  !> `side_extrados`, from left to right; unused entries are -1 and 0. A direction in
  !> which no admissible mechanism exists has lambda = huge(1.0_dp) and no hinges.
  type :: limit_result_t
    real(dp) :: lambda_pos = huge(1.0_dp)   !! collapse multiplier, load towards +x
    real(dp) :: lambda_neg = huge(1.0_dp)   !! collapse multiplier, load towards -x
    integer :: n_hinges_pos = 0             !! 4 for an arch, 1 for a stack
    integer :: n_hinges_neg = 0
    integer :: hinges_pos(4) = -1           !! joints of the +x mechanism
    integer :: sides_pos(4) = 0             !! hinge sides of the +x mechanism
    integer :: hinges_neg(4) = -1           !! joints of the -x mechanism
    integer :: sides_neg(4) = 0             !! hinge sides of the -x mechanism
    real(dp) :: lambda_static_pos = huge(1.0_dp)  !! multiplier of the thrust line through the hinges
    real(dp) :: lambda_static_neg = huge(1.0_dp)
    !> The thrust line through the hinges stays within every joint and gives the same
    !> multiplier: the static and kinematic bounds meet.
    logical :: bounds_meet_pos = .false.
    logical :: bounds_meet_neg = .false.
    !> (0:n) position of the joint resultant along each joint: 0 at the intrados pivot,
    !> 1 at the extrados pivot (inside the joint between them).
    real(dp), allocatable :: thrust_fraction_pos(:), thrust_fraction_neg(:)
    !> (0:n) |shear| / normal force of each joint resultant at collapse (huge if not in
    !> compression; 0 for the unloaded top joint of a stack).
    real(dp), allocatable :: shear_ratio_pos(:), shear_ratio_neg(:)
    !> Joints whose shear ratio exceeds the friction coefficient: sliding governs there
    !> instead of hinging (empty when hinging governs).
    integer, allocatable :: sliding_joints_pos(:), sliding_joints_neg(:)
  end type limit_result_t

  !> One mechanism: its multiplier and hinges.
  type :: mechanism_t
    real(dp) :: lambda = huge(1.0_dp)
    integer :: n_hinges = 0
    integer :: joint(4) = -1
    integer :: side(4) = 0
  end type mechanism_t

  !> A chain prepared for the search: pivots, opening signs, prefix sums of the loads.
  type :: chain_work_t
    integer :: n = 0
    logical :: free_top = .false.
    real(dp), allocatable :: pivot(:, :, :)   ! (2, 0:n, side) hinge points, inset applied [m]
    real(dp), allocatable :: opening(:, :)    ! (0:n, side) +-1: sign of the relative rotation that opens
    real(dp), allocatable :: normal(:, :)     ! (2, 0:n) unit normal from block j into block j+1
    real(dp), allocatable :: tangent(:, :)    ! (2, 0:n) unit vector from intrados to extrados
    real(dp), allocatable :: w_sum(:)         ! (0:n) weight of blocks 1..j
    real(dp), allocatable :: wx_sum(:)        ! (0:n) sum of weight * x of blocks 1..j
    real(dp), allocatable :: wy_sum(:)        ! (0:n) sum of weight * y of blocks 1..j
    real(dp) :: span_m = 0.0_dp               ! size of the chain [m]
  end type chain_work_t

  !> Forces of a thrust-line solution: reaction (H, V) of the left support on block 1,
  !> its moment about the origin, and the multiplier, for the load direction `dir`.
  type :: thrust_state_t
    real(dp) :: h = 0.0_dp, v = 0.0_dp, m0 = 0.0_dp, lambda = 0.0_dp, dir = 1.0_dp
  end type thrust_state_t

contains

  !> The chain of an arch built by `build_arch`: voussoirs 1..n with their polygon areas
  !> as weights (lambda does not depend on density or width) and centroids, joints 0..n.
  pure subroutine arch_chain(arch, chain, status)
    type(assembly_t), intent(in) :: arch         !! an arch from `build_arch`
    type(block_chain_t), intent(out) :: chain
    type(status_t), intent(inout) :: status
    integer :: j, n

    n = arch%n_voussoirs
    if (n < 1 .or. .not. allocated(arch%joint_intrados_xy) .or. .not. allocated(arch%joint_extrados_xy)) then
      call fail(status, 'limit analysis: the assembly is not an arch (no voussoirs or joints)')
      return
    end if
    if (arch%n_bodies < n .or. size(arch%joint_intrados_xy, 2) /= n + 1 &
        .or. size(arch%joint_extrados_xy, 2) /= n + 1) then
      call fail(status, 'limit analysis: the arch joints do not match its voussoirs')
      return
    end if
    chain%n_blocks = n
    chain%free_top = .false.
    allocate (chain%weight(n), chain%centroid_xy(2, n))
    allocate (chain%joint_intrados_xy(2, 0:n), chain%joint_extrados_xy(2, 0:n))
    do j = 1, n
      chain%weight(j) = polygon_area(arch%polygon(j)%xy)
      chain%centroid_xy(:, j) = polygon_centroid(arch%polygon(j)%xy)
    end do
    chain%joint_intrados_xy = arch%joint_intrados_xy
    chain%joint_extrados_xy = arch%joint_extrados_xy
  end subroutine arch_chain

  !> Horizontal collapse multipliers (towards +x and -x) of an arch from `build_arch`,
  !> with the hinge pivots set in by `inset_m` and the sliding check against `friction`
  !> (at joint j against `joint_friction(j)` where that is >= 0, as in the dynamics).
  pure subroutine horizontal_capacity(arch, inset_m, friction, result, status, joint_friction)
    type(assembly_t), intent(in) :: arch         !! an arch from `build_arch`
    real(dp), intent(in) :: inset_m              !! pivot distance from the joint ends [m]
    real(dp), intent(in) :: friction             !! Coulomb coefficient of the joints
    type(limit_result_t), intent(out) :: result
    type(status_t), intent(inout) :: status
    real(dp), intent(in), optional :: joint_friction(0:) !! per joint; < 0: `friction`
    type(block_chain_t) :: chain

    if (allocated(arch%role)) then
      if (any(arch%role == role_restraint)) then
        call fail(status, 'limit analysis: restraint brackets are not modelled; '// &
                  'analyse the arch without restrained springings')
        return
      end if
    end if
    call arch_chain(arch, chain, status)
    if (.not. status%ok) return
    call chain_capacity(chain, inset_m, friction, result, status, joint_friction)
  end subroutine horizontal_capacity

  !> Horizontal collapse multipliers of a generic chain of blocks (see `block_chain_t`).
  !>
  !> Arch chains need at least 3 blocks (a four-hinge mechanism), stacks at least 1.
  pure subroutine chain_capacity(chain, inset_m, friction, result, status, joint_friction)
    type(block_chain_t), intent(in) :: chain
    real(dp), intent(in) :: inset_m              !! pivot distance from the joint ends [m]
    real(dp), intent(in) :: friction             !! Coulomb coefficient of the joints
    type(limit_result_t), intent(out) :: result
    type(status_t), intent(inout) :: status
    real(dp), intent(in), optional :: joint_friction(0:) !! per joint; < 0: `friction`
    type(chain_work_t) :: work
    type(mechanism_t) :: best_pos, best_neg
    real(dp), allocatable :: mu(:)
    integer :: j

    if (.not. (friction >= 0.0_dp)) then
      call fail(status, 'limit analysis: friction must be >= 0')
      return
    end if
    call prepare_chain(chain, inset_m, work, status)
    if (.not. status%ok) return
    allocate (mu(0:work%n))
    mu = friction
    if (present(joint_friction)) then
      do j = 0, min(work%n, ubound(joint_friction, 1))
        if (joint_friction(j) >= 0.0_dp) mu(j) = joint_friction(j)
      end do
    end if

    if (work%free_top) then
      call search_stack(work, best_pos, best_neg)
    else
      call search_arch(work, best_pos, best_neg)
    end if

    result%lambda_pos = best_pos%lambda
    result%n_hinges_pos = best_pos%n_hinges
    result%hinges_pos = best_pos%joint
    result%sides_pos = best_pos%side
    result%lambda_neg = best_neg%lambda
    result%n_hinges_neg = best_neg%n_hinges
    result%hinges_neg = best_neg%joint
    result%sides_neg = best_neg%side

    call verify_mechanism(work, best_pos, 1.0_dp, mu, result%lambda_static_pos, &
                          result%bounds_meet_pos, result%thrust_fraction_pos, &
                          result%shear_ratio_pos, result%sliding_joints_pos)
    call verify_mechanism(work, best_neg, -1.0_dp, mu, result%lambda_static_neg, &
                          result%bounds_meet_neg, result%thrust_fraction_neg, &
                          result%shear_ratio_neg, result%sliding_joints_neg)
  end subroutine chain_capacity

  !> Validate the chain and precompute pivots, opening signs and load sums.
  pure subroutine prepare_chain(chain, inset_m, work, status)
    type(block_chain_t), intent(in) :: chain
    real(dp), intent(in) :: inset_m
    type(chain_work_t), intent(out) :: work
    type(status_t), intent(inout) :: status
    real(dp) :: e(2), p(2), mid(2), length_m, toward(2)
    real(dp), allocatable :: joint_int(:, :), joint_ext(:, :), centroid(:, :), weight(:)
    integer :: j, n, side
    character(len=16) :: id

    n = chain%n_blocks
    if (.not. chain%free_top .and. n < 3) then
      call fail(status, 'limit analysis: a chain between two supports needs at least 3 blocks '// &
                'for a four-hinge mechanism')
      return
    end if
    if (n < 1) then
      call fail(status, 'limit analysis: the chain has no block')
      return
    end if
    if (.not. (allocated(chain%weight) .and. allocated(chain%centroid_xy) .and. &
               allocated(chain%joint_intrados_xy) .and. allocated(chain%joint_extrados_xy))) then
      call fail(status, 'limit analysis: chain arrays not allocated')
      return
    end if
    if (size(chain%weight) /= n .or. any(shape(chain%centroid_xy) /= [2, n]) .or. &
        any(shape(chain%joint_intrados_xy) /= [2, n + 1]) .or. &
        any(shape(chain%joint_extrados_xy) /= [2, n + 1])) then
      call fail(status, 'limit analysis: chain arrays do not match n_blocks')
      return
    end if
    if (any(.not. (chain%weight > 0.0_dp))) then
      call fail(status, 'limit analysis: every block weight must be > 0')
      return
    end if
    if (.not. (inset_m >= 0.0_dp)) then
      call fail(status, 'limit analysis: inset_m must be >= 0')
      return
    end if

    ! Copy with fixed bounds: the caller's arrays may start at any index.
    allocate (joint_int(2, 0:n), joint_ext(2, 0:n), centroid(2, n), weight(n))
    weight(:) = chain%weight
    joint_int(:, :) = chain%joint_intrados_xy
    joint_ext(:, :) = chain%joint_extrados_xy
    centroid(:, :) = chain%centroid_xy
    work%n = n
    work%free_top = chain%free_top
    allocate (work%pivot(2, 0:n, 2), work%opening(0:n, 2), work%normal(2, 0:n), work%tangent(2, 0:n))
    allocate (work%w_sum(0:n), work%wx_sum(0:n), work%wy_sum(0:n))

    do j = 0, n
      e = joint_ext(:, j) - joint_int(:, j)
      length_m = norm2(e)
      if (j < n .or. .not. chain%free_top) then
        if (.not. (length_m > 2.0_dp*inset_m)) then
          write (id, '(i0)') j
          call fail(status, 'limit analysis: joint '//trim(id)// &
                    ' is not longer than twice inset_m (0 <= inset_m < joint length / 2)')
          return
        end if
      end if
      if (length_m <= 0.0_dp) then
        ! Only the unloaded top joint of a stack may be degenerate.
        e = [1.0_dp, 0.0_dp]
      else
        e = e/length_m
      end if
      work%tangent(:, j) = e
      ! Normal from block j into block j+1, oriented by the centroids on either side.
      p = [-e(2), e(1)]
      mid = 0.5_dp*(joint_int(:, j) + joint_ext(:, j))
      if (j < n) then
        toward = centroid(:, j + 1) - mid
      else
        toward = mid - centroid(:, j)
      end if
      work%normal(:, j) = merge(p, -p, dot_product(toward, p) >= 0.0_dp)
      work%pivot(:, j, side_intrados) = joint_int(:, j) + inset_m*e
      work%pivot(:, j, side_extrados) = joint_ext(:, j) - inset_m*e
      ! Relative rotation (block j+1 minus block j) that lifts the other end off.
      do side = 1, 2
        work%opening(j, side) = sign(1.0_dp, cross2(work%pivot(:, j, 3 - side) - work%pivot(:, j, side), &
                                                     work%normal(:, j)))
      end do
    end do

    work%w_sum(0) = 0.0_dp
    work%wx_sum(0) = 0.0_dp
    work%wy_sum(0) = 0.0_dp
    do j = 1, n
      work%w_sum(j) = work%w_sum(j - 1) + weight(j)
      work%wx_sum(j) = work%wx_sum(j - 1) + weight(j)*centroid(1, j)
      work%wy_sum(j) = work%wy_sum(j - 1) + weight(j)*centroid(2, j)
    end do
    work%span_m = max(maxval(abs(joint_int)), maxval(abs(joint_ext)), &
                      maxval(abs(centroid)))
  end subroutine prepare_chain

  !> All admissible four-hinge mechanisms of an arch chain: hinges A, B, C, D at joints
  !> a < b < c < d; blocks a+1..b turn about A, blocks c+1..d about D, blocks b+1..c
  !> about the intersection of AB and CD. With omega1 = 1 the velocities of B and C
  !> match when omega2 (C - B) + omega3 (D - C) = A - B.
  pure subroutine search_arch(work, best_pos, best_neg)
    type(chain_work_t), intent(in) :: work
    type(mechanism_t), intent(inout) :: best_pos, best_neg
    real(dp) :: pa(2), pb(2), pc(2), pd(2), u(2), v(2), r(2), vb(2)
    real(dp) :: det, omega2, omega3, orient, omega_max, tol_theta, tol_power, u_sq
    real(dp) :: w1, pg1, ph1, w2, x2, y2, w3, pg, ph, lambda, scale
    integer :: n, a, b, c, d, sa, sb, sc, sd

    n = work%n
    scale = work%w_sum(n)*work%span_m
    do a = 0, n - 3
      do sa = 1, 2
        pa = work%pivot(:, a, sa)
        orient = work%opening(a, sa)    ! omega1 = orient opens hinge A
        do b = a + 1, n - 2
          w1 = work%w_sum(b) - work%w_sum(a)
          do sb = 1, 2
            pb = work%pivot(:, b, sb)
            ! Chain 1 turns about A with omega1 = 1.
            pg1 = (work%wx_sum(b) - work%wx_sum(a)) - w1*pa(1)
            ph1 = -((work%wy_sum(b) - work%wy_sum(a)) - w1*pa(2))
            vb = [-(pb(2) - pa(2)), pb(1) - pa(1)]
            r = pa - pb
            do c = b + 1, n - 1
              w2 = work%w_sum(c) - work%w_sum(b)
              x2 = (work%wx_sum(c) - work%wx_sum(b)) - w2*pb(1)
              y2 = (work%wy_sum(c) - work%wy_sum(b)) - w2*pb(2)
              do sc = 1, 2
                pc = work%pivot(:, c, sc)
                u = pc - pb
                u_sq = dot_product(u, u)
                do d = c + 1, n
                  w3 = work%w_sum(d) - work%w_sum(c)
                  do sd = 1, 2
                    pd = work%pivot(:, d, sd)
                    v = pd - pc
                    ! Cross products written out: this is the innermost loop.
                    det = u(1)*v(2) - u(2)*v(1)
                    ! B, C, D in line: chains 2 and 3 cannot move.
                    if (det**2 <= degenerate_rel_tol**2*u_sq*(v(1)**2 + v(2)**2)) cycle
                    omega2 = (r(1)*v(2) - r(2)*v(1))/det
                    omega3 = (u(1)*r(2) - u(2)*r(1))/det
                    omega_max = max(1.0_dp, abs(omega2), abs(omega3))
                    tol_theta = degenerate_rel_tol*omega_max
                    ! Every hinge must open: relative rotation times its opening sign >= 0.
                    if (orient*work%opening(b, sb)*(omega2 - 1.0_dp) < -tol_theta) cycle
                    if (orient*work%opening(c, sc)*(omega3 - omega2) < -tol_theta) cycle
                    if (orient*work%opening(d, sd)*(-omega3) < -tol_theta) cycle
                    ! Power of unit weights (sum W v_y) and of a unit horizontal load (sum W v_x).
                    pg = pg1 + w2*vb(2) + omega2*x2 &
                         + omega3*((work%wx_sum(d) - work%wx_sum(c)) - w3*pd(1))
                    ph = ph1 + w2*vb(1) - omega2*y2 &
                         - omega3*((work%wy_sum(d) - work%wy_sum(c)) - w3*pd(2))
                    pg = orient*pg
                    ph = orient*ph
                    tol_power = degenerate_rel_tol*omega_max*scale
                    if (ph > tol_power) then
                      lambda = pg/ph
                      if (lambda < best_pos%lambda) &
                        best_pos = mechanism_t(lambda, 4, [a, b, c, d], [sa, sb, sc, sd])
                    else if (ph < -tol_power) then
                      lambda = -pg/ph
                      if (lambda < best_neg%lambda) &
                        best_neg = mechanism_t(lambda, 4, [a, b, c, d], [sa, sb, sc, sd])
                    end if
                  end do
                end do
              end do
            end do
          end do
        end do
      end do
    end do
  end subroutine search_arch

  !> All single-hinge mechanisms of a stack: blocks a+1..n turn about a pivot of joint a.
  pure subroutine search_stack(work, best_pos, best_neg)
    type(chain_work_t), intent(in) :: work
    type(mechanism_t), intent(inout) :: best_pos, best_neg
    real(dp) :: p(2), w_above, pg, ph, lambda, tol_power
    integer :: n, a, side

    n = work%n
    tol_power = degenerate_rel_tol*work%w_sum(n)*work%span_m
    do a = 0, n - 1
      w_above = work%w_sum(n) - work%w_sum(a)
      do side = 1, 2
        p = work%pivot(:, a, side)
        pg = work%opening(a, side)*((work%wx_sum(n) - work%wx_sum(a)) - w_above*p(1))
        ph = -work%opening(a, side)*((work%wy_sum(n) - work%wy_sum(a)) - w_above*p(2))
        if (ph > tol_power) then
          lambda = pg/ph
          if (lambda < best_pos%lambda) best_pos = mechanism_t(lambda, 1, [a, -1, -1, -1], [side, 0, 0, 0])
        else if (ph < -tol_power) then
          lambda = -pg/ph
          if (lambda < best_neg%lambda) best_neg = mechanism_t(lambda, 1, [a, -1, -1, -1], [side, 0, 0, 0])
        end if
      end do
    end do
  end subroutine search_stack

  !> Static side of a mechanism: the thrust line through its hinges, its multiplier, its
  !> position in every joint and the shear ratios of the joint resultants.
  pure subroutine verify_mechanism(work, mech, dir, friction, lambda_static, bounds_meet, &
                                   thrust_fraction, shear_ratio, sliding_joints)
    type(chain_work_t), intent(in) :: work
    type(mechanism_t), intent(in) :: mech
    real(dp), intent(in) :: dir
    real(dp), intent(in) :: friction(0:)         !! Coulomb coefficient of each joint
    real(dp), intent(out) :: lambda_static
    logical, intent(out) :: bounds_meet
    real(dp), allocatable, intent(out) :: thrust_fraction(:), shear_ratio(:)
    integer, allocatable, intent(out) :: sliding_joints(:)
    type(thrust_state_t) :: state
    real(dp) :: force(2), moment, h_int, h_ext, normal_force, shear_force
    logical :: solved, inside(0:work%n)
    integer :: j, n, n_loaded

    n = work%n
    allocate (thrust_fraction(0:n), shear_ratio(0:n), sliding_joints(0))
    thrust_fraction = 0.0_dp
    shear_ratio = 0.0_dp
    lambda_static = huge(1.0_dp)
    bounds_meet = .false.
    if (mech%n_hinges == 0) return

    call thrust_through_hinges(work, mech, dir, state, solved)
    if (.not. solved) return
    lambda_static = state%lambda

    n_loaded = merge(n - 1, n, work%free_top)
    inside = .true.
    do j = 0, n_loaded
      call joint_resultant(work, state, j, force, moment)
      h_int = cross2(work%pivot(:, j, side_intrados), force) - moment
      h_ext = cross2(work%pivot(:, j, side_extrados), force) - moment
      normal_force = dot_product(force, work%normal(:, j))
      shear_force = dot_product(force, work%tangent(:, j))
      if (abs(h_int - h_ext) > 0.0_dp) then
        thrust_fraction(j) = h_int/(h_int - h_ext)
      else
        thrust_fraction(j) = huge(1.0_dp)
      end if
      inside(j) = normal_force > 0.0_dp .and. thrust_fraction(j) >= -thrust_rel_tol &
                  .and. thrust_fraction(j) <= 1.0_dp + thrust_rel_tol
      if (normal_force > 0.0_dp) then
        shear_ratio(j) = abs(shear_force)/normal_force
      else
        shear_ratio(j) = huge(1.0_dp)
      end if
      if (shear_ratio(j) > friction(j)) sliding_joints = [sliding_joints, j]
    end do
    bounds_meet = all(inside) .and. &
                  abs(lambda_static - mech%lambda) <= lambda_tol*max(1.0_dp, abs(mech%lambda))
  end subroutine verify_mechanism

  !> Resultant force transmitted by joint j from block j to block j+1 and its moment
  !> about the origin, for the thrust state.
  pure subroutine joint_resultant(work, state, j, force, moment)
    type(chain_work_t), intent(in) :: work
    type(thrust_state_t), intent(in) :: state
    integer, intent(in) :: j
    real(dp), intent(out) :: force(2), moment
    force = [state%h + state%dir*state%lambda*work%w_sum(j), state%v - work%w_sum(j)]
    moment = state%m0 - work%wx_sum(j) - state%dir*state%lambda*work%wy_sum(j)
  end subroutine joint_resultant

  !> The thrust line through the hinges of a mechanism. For an arch the four hinge
  !> conditions fix the support reaction (H, V, M0) and lambda; for a stack the support
  !> reaction balances the loads and the one hinge fixes lambda.
  pure subroutine thrust_through_hinges(work, mech, dir, state, solved)
    type(chain_work_t), intent(in) :: work
    type(mechanism_t), intent(in) :: mech
    real(dp), intent(in) :: dir
    type(thrust_state_t), intent(out) :: state
    logical, intent(out) :: solved
    real(dp) :: mat(4, 4), rhs(4), x(4), p(2), w_above, wx_above, wy_above, den
    integer :: k, j, n

    n = work%n
    state%dir = dir
    solved = .false.
    if (work%free_top) then
      ! Hinge at joint j: the loads above act through the pivot.
      j = mech%joint(1)
      p = work%pivot(:, j, mech%side(1))
      w_above = work%w_sum(n) - work%w_sum(j)
      wx_above = work%wx_sum(n) - work%wx_sum(j)
      wy_above = work%wy_sum(n) - work%wy_sum(j)
      den = dir*(p(2)*w_above - wy_above)
      if (abs(den) <= degenerate_rel_tol*work%w_sum(n)*work%span_m) return
      state%lambda = (wx_above - p(1)*w_above)/den
      state%h = -dir*state%lambda*work%w_sum(n)
      state%v = work%w_sum(n)
      state%m0 = work%wx_sum(n) + dir*state%lambda*work%wy_sum(n)
      solved = .true.
    else
      ! Thrust through pivot P of joint j: cross(P, R_j) - M_j = 0, linear in (H, V, M0, lambda).
      do k = 1, 4
        j = mech%joint(k)
        p = work%pivot(:, j, mech%side(k))
        mat(k, :) = [-p(2), p(1), -1.0_dp, dir*(work%wy_sum(j) - p(2)*work%w_sum(j))]
        rhs(k) = p(1)*work%w_sum(j) - work%wx_sum(j)
      end do
      call solve4(mat, rhs, x, solved)
      if (.not. solved) return
      state%h = x(1)
      state%v = x(2)
      state%m0 = x(3)
      state%lambda = x(4)
    end if
  end subroutine thrust_through_hinges

  !> Solve a 4x4 linear system by Gaussian elimination with partial pivoting.
  pure subroutine solve4(mat, rhs, x, solved)
    real(dp), intent(in) :: mat(4, 4), rhs(4)
    real(dp), intent(out) :: x(4)
    logical, intent(out) :: solved
    real(dp) :: a(4, 5), row(5), col_scale(4)
    integer :: i, k, p

    a(:, 1:4) = mat
    a(:, 5) = rhs
    ! Scale the columns so the unknowns (forces, moment, multiplier) are comparable.
    do k = 1, 4
      col_scale(k) = maxval(abs(a(:, k)))
      if (col_scale(k) <= 0.0_dp) then
        solved = .false.
        x = 0.0_dp
        return
      end if
      a(:, k) = a(:, k)/col_scale(k)
    end do
    solved = .true.
    do k = 1, 4
      p = k - 1 + maxloc(abs(a(k:4, k)), 1)
      if (abs(a(p, k)) <= degenerate_rel_tol) then
        solved = .false.
        x = 0.0_dp
        return
      end if
      if (p /= k) then
        row = a(k, :)
        a(k, :) = a(p, :)
        a(p, :) = row
      end if
      do i = k + 1, 4
        a(i, k:5) = a(i, k:5) - a(i, k)/a(k, k)*a(k, k:5)
      end do
    end do
    do k = 4, 1, -1
      x(k) = (a(k, 5) - dot_product(a(k, k + 1:4), x(k + 1:4)))/a(k, k)
    end do
    x = x/col_scale
  end subroutine solve4

end module voussoir_limit_analysis
