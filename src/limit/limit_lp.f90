!> The rigid-block limit analysis of any 2D assembly by linear programming (Livesley;
!> Gilbert's form used by RING), solved by GLPK (voussoir_glpk): normal and shear forces
!> at the interfaces (voussoir_block_interfaces), equilibrium of every block that is not
!> driven under its weight plus lambda times a live load, no tension, Coulomb friction;
!> maximise lambda. The row duals are the virtual velocities of the blocks: the mechanism.
!> docs/limit_analysis.md, "Any assembly".
module voussoir_limit_lp
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa
  use voussoir_assembly, only: assembly_t
  use voussoir_geometry, only: polygon_area, polygon_centroid, cross2
  use voussoir_block_interfaces, only: interface_set_t
  use voussoir_placed_loads, only: placed_loads_t
  use voussoir_glpk, only: lp_solve, lp_free, lp_lower, lp_upper, lp_double, lp_fixed, &
                           lp_optimal, lp_infeasible, lp_unbounded
  implicit none
  private

  public :: block_loads_t, lp_result_t, block_loads, add_placed_loads, lp_capacity, nonassociative_capacity
  public :: joint_closed, joint_hinge, joint_sliding, joint_open, joint_mode_name
  public :: lp_outcome_optimal, lp_outcome_infeasible, lp_outcome_unbounded

  integer, parameter :: joint_closed = 0   !! no relative motion
  integer, parameter :: joint_hinge = 1    !! turns about one end, the other opens
  integer, parameter :: joint_sliding = 2  !! slides (and may open)
  integer, parameter :: joint_open = 3     !! both ends separate, no sliding
  integer, parameter :: lp_outcome_optimal = lp_optimal, lp_outcome_infeasible = lp_infeasible, &
                        lp_outcome_unbounded = lp_unbounded

  !> Dead and live loads of the blocks: each block's resultant force and its moment
  !> about the block's centroid.
  type :: block_loads_t
    real(dp), allocatable :: weight_n(:)       !! dead load of each block [N], downwards
    real(dp), allocatable :: dead_n(:, :)      !! (2, n_bodies) dead point loads [N], beside the weight
    real(dp), allocatable :: dead_moment_nm(:) !! their moment about the centroid [N m], counter-clockwise
    real(dp), allocatable :: live_n(:, :)      !! (2, n_bodies) live load per unit lambda [N]
    real(dp), allocatable :: live_moment_nm(:) !! its moment about the centroid per unit lambda [N m]
    real(dp), allocatable :: centroid(:, :)    !! (2, n_bodies) [m]
    !> Bounded forces (a fill's pressure): on block body(k) at xy(:, k) along dir(:, k),
    !> between lo_n(k) and hi_n(k) [N]; the LP chooses each.
    integer :: n_bounded = 0
    integer, allocatable :: bounded_body(:)
    real(dp), allocatable :: bounded_xy(:, :), bounded_dir(:, :), bounded_lo_n(:), bounded_hi_n(:)
  end type block_loads_t

  !> The solution of one linear programme.
  type :: lp_result_t
    integer :: outcome = lp_optimal
    real(dp) :: load_factor = 0.0_dp        !! lambda of the static field (lower bound)
    real(dp) :: load_factor_upper = 0.0_dp  !! lambda of the mechanism by the work equation (upper bound)
    real(dp), allocatable :: end_xy(:, :, :) !! (2, 2, n_interfaces) the ends the normal forces act at [m]
    real(dp), allocatable :: normal_n(:, :) !! (2, n_interfaces) normal force at each end [N], >= 0
    real(dp), allocatable :: shear_n(:)     !! shear force [N] on body(2), along the normal turned +90 deg
    real(dp), allocatable :: velocity(:, :) !! (3, n_bodies) u_x, u_y at the centroid, omega; live power 1
    integer, allocatable :: mode(:)         !! joint_closed / _hinge / _sliding / _open per interface
    integer, allocatable :: pivot_end(:)    !! the end a hinge turns about (1 or 2), else 0
    real(dp), allocatable :: bounded_n(:)   !! each bounded force's value at collapse [N]
    integer :: unbounded_body = 0           !! a block of the interface along which lambda grows, if known
  end type lp_result_t

contains

  !> Weights (density x area x width x g; each block's own density where the assembly gives
  !> it) and the live load of a horizontal acceleration lambda g towards +x: lambda times
  !> the weight, horizontally.
  pure subroutine block_loads(asm, density_kg_m3, width_m, g_m_s2, loads)
    type(assembly_t), intent(in) :: asm
    real(dp), intent(in) :: density_kg_m3, width_m, g_m_s2
    type(block_loads_t), intent(out) :: loads
    real(dp) :: rho
    integer :: b
    allocate (loads%weight_n(asm%n_bodies), loads%live_n(2, asm%n_bodies), loads%centroid(2, asm%n_bodies), &
              loads%dead_n(2, asm%n_bodies), loads%dead_moment_nm(asm%n_bodies), loads%live_moment_nm(asm%n_bodies))
    loads%dead_n = 0.0_dp
    loads%dead_moment_nm = 0.0_dp
    loads%live_moment_nm = 0.0_dp
    do b = 1, asm%n_bodies
      rho = density_kg_m3
      if (allocated(asm%density_kg_m3)) rho = asm%density_kg_m3(b)   ! a bridge's parts
      loads%weight_n(b) = rho*polygon_area(asm%polygon(b)%xy)*width_m*g_m_s2
      loads%centroid(:, b) = polygon_centroid(asm%polygon(b)%xy)
      loads%live_n(:, b) = [loads%weight_n(b), 0.0_dp]
    end do
  end subroutine block_loads

  !> Add the point loads `placed` (each a force and its moment about its block's
  !> centroid): the dead ones to the weights; the live ones, if any, replace the
  !> horizontal acceleration as the live load.
  pure subroutine add_placed_loads(placed, loads)
    type(placed_loads_t), intent(in) :: placed
    type(block_loads_t), intent(inout) :: loads
    real(dp) :: moment
    integer :: k, b
    if (allocated(placed%pressure_block)) then   ! a fill's pressure: bounded forces
      loads%n_bounded = placed%n_pressure
      loads%bounded_body = placed%pressure_block
      loads%bounded_xy = placed%pressure_xy
      loads%bounded_dir = placed%pressure_dir
      loads%bounded_lo_n = placed%pressure_lo_n
      loads%bounded_hi_n = placed%pressure_hi_n
    end if
    if (any(placed%live)) then
      loads%live_n = 0.0_dp
      loads%live_moment_nm = 0.0_dp
    end if
    do k = 1, placed%n
      b = placed%block(k)
      moment = cross2(placed%xy(:, k) - loads%centroid(:, b), placed%force_n(:, k))
      if (placed%live(k)) then
        loads%live_n(:, b) = loads%live_n(:, b) + placed%force_n(:, k)
        loads%live_moment_nm(b) = loads%live_moment_nm(b) + moment
      else
        loads%dead_n(:, b) = loads%dead_n(:, b) + placed%force_n(:, k)
        loads%dead_moment_nm(b) = loads%dead_moment_nm(b) + moment
      end if
    end do
  end subroutine add_placed_loads

  !> Maximise lambda. Friction of interface k: |S| <= friction(k) (N1 + N2) + cohesion_n(k)
  !> (the Coulomb problem with cohesion_n = 0; with friction = 0 and cohesion_n = mu N of
  !> a previous solution, one step of the non-associative iteration). lambda >= 0:
  !> infeasible means that the dead load alone brings the assembly down.
  subroutine lp_capacity(asm, faces, loads, friction, cohesion_n, res, status)
    type(assembly_t), intent(in) :: asm
    type(interface_set_t), intent(in) :: faces
    type(block_loads_t), intent(in) :: loads
    real(dp), intent(in) :: friction(:), cohesion_n(:)
    type(lp_result_t), intent(out) :: res
    type(status_t), intent(inout) :: status
    integer, allocatable :: row_of(:), row_kind(:), col_kind(:), ia(:), ja(:)
    real(dp), allocatable :: row_lo(:), row_hi(:), col_lo(:), col_hi(:), obj(:), ar(:), x(:), dual(:)
    real(dp) :: scale_n, objective
    logical, allocatable :: keep(:)
    integer :: n_rows, n_cols, nf, ne, k, b, ray

    nf = faces%n
    ! Rows: 3 per free block (x, y, moment about the centroid), then 2 per interface.
    allocate (row_of(asm%n_bodies))
    row_of = 0
    n_rows = 0
    do b = 1, asm%n_bodies
      if (asm%driven(b)) cycle
      row_of(b) = n_rows + 1
      n_rows = n_rows + 3
    end do
    n_rows = n_rows + 2*nf
    n_cols = 3*nf + 1 + loads%n_bounded   ! N1, N2, S per interface, lambda, then the bounded forces
    scale_n = max(maxval(loads%weight_n, mask=.not. asm%driven), maxval(norm2(loads%live_n, dim=1)), tiny(1.0_dp))
    allocate (row_kind(n_rows), row_lo(n_rows), row_hi(n_rows), col_kind(n_cols), col_lo(n_cols), &
              col_hi(n_cols), obj(n_cols), ia(24*nf + 3*asm%n_bodies + 3*loads%n_bounded), &
              ja(24*nf + 3*asm%n_bodies + 3*loads%n_bounded), ar(24*nf + 3*asm%n_bodies + 3*loads%n_bounded))
    row_kind = lp_fixed
    row_lo = 0.0_dp
    do b = 1, asm%n_bodies
      ! Interface forces + lambda live = -(dead load): the weight and the dead point loads.
      if (row_of(b) > 0) row_lo(row_of(b):row_of(b) + 2) = [-loads%dead_n(1, b), loads%weight_n(b) - loads%dead_n(2, b), &
                                                            -loads%dead_moment_nm(b)]/scale_n
    end do
    row_hi = row_lo
    col_kind = [([lp_lower, lp_lower, lp_free], k=1, nf), lp_lower, (lp_double, k=1, loads%n_bounded)]
    col_lo = 0.0_dp
    col_hi = 0.0_dp
    obj = 0.0_dp
    obj(3*nf + 1) = 1.0_dp
    ne = 0
    do k = 1, nf
      call interface_columns(faces, k, loads%centroid, row_of, ia, ja, ar, ne)
      ! S - mu (N1 + N2) <= c and -S - mu (N1 + N2) <= c
      row_kind(n_rows - 2*nf + 2*k - 1:n_rows - 2*nf + 2*k) = lp_upper
      row_hi(n_rows - 2*nf + 2*k - 1:n_rows - 2*nf + 2*k) = cohesion_n(k)/scale_n
      call put(n_rows - 2*nf + 2*k - 1, [3*k - 2, 3*k - 1, 3*k], [-friction(k), -friction(k), 1.0_dp])
      call put(n_rows - 2*nf + 2*k, [3*k - 2, 3*k - 1, 3*k], [-friction(k), -friction(k), -1.0_dp])
    end do
    call bounded_columns(loads, 3*nf + 1, scale_n, row_of, col_kind, col_lo, col_hi, ia, ja, ar, ne)
    do b = 1, asm%n_bodies     ! the live load, lambda times live_n and its moment
      if (row_of(b) == 0) cycle
      call put(row_of(b), [3*nf + 1], [loads%live_n(1, b)/scale_n])
      call put(row_of(b) + 1, [3*nf + 1], [loads%live_n(2, b)/scale_n])
      if (loads%live_moment_nm(b) /= 0.0_dp) call put(row_of(b) + 2, [3*nf + 1], [loads%live_moment_nm(b)/scale_n])
    end do

    ! Moment arms of round-off size (1e-17 where a force passes through a centroid) ruin
    ! GLPK's scaling and then its simplex: drop them.
    keep = abs(ar(1:ne)) > 1.0e-12_dp*maxval(abs(ar(1:ne)))
    allocate (x(n_cols), dual(n_rows))
    call lp_solve(row_kind, row_lo, row_hi, col_kind, col_lo, col_hi, obj, pack(ia(1:ne), keep), &
                  pack(ja(1:ne), keep), pack(ar(1:ne), keep), x, dual, objective, res%outcome, ray)
    select case (res%outcome)
    case (lp_optimal)
      res%load_factor = objective
      res%end_xy = faces%end_xy
      res%normal_n = scale_n*reshape([(x(3*k - 2:3*k - 1), k=1, nf)], [2, nf])
      res%shear_n = scale_n*[(x(3*k), k=1, nf)]
      res%bounded_n = scale_n*x(3*nf + 2:n_cols)
      call velocities_from_duals(asm, loads, row_of, dual, res%velocity)
      call classify_joints(faces, loads%centroid, res%velocity, res%mode, res%pivot_end)
      res%load_factor_upper = work_load_factor(faces, loads, res%velocity, cohesion_n)
    case (lp_infeasible)
      call fail(status, 'the dead load alone brings the assembly down: no equilibrium without tension '// &
                'and within friction carries the weights (the linear programme is infeasible)')
    case (lp_unbounded)
      call refuse_unbounded(asm, faces, loads, ray, 3*nf + 1, res, status)
    case default
      call fail(status, 'GLPK failed to solve the linear programme of the limit analysis')
    end select

  contains

    subroutine put(row, cols, values)
      integer, intent(in) :: row, cols(:)
      real(dp), intent(in) :: values(:)
      integer :: c
      do c = 1, size(cols)
        ne = ne + 1
        ia(ne) = row
        ja(ne) = cols(c)
        ar(ne) = values(c)
      end do
    end subroutine put

  end subroutine lp_capacity

  !> The columns of the bounded forces, after column `first - 1`: their bounds (scaled by
  !> `scale_n`; fixed where they meet) and their force and moment on their blocks' rows.
  pure subroutine bounded_columns(loads, first, scale_n, row_of, col_kind, col_lo, col_hi, ia, ja, ar, ne)
    type(block_loads_t), intent(in) :: loads
    integer, intent(in) :: first, row_of(:)
    real(dp), intent(in) :: scale_n
    integer, intent(inout) :: col_kind(:), ia(:), ja(:), ne
    real(dp), intent(inout) :: col_lo(:), col_hi(:), ar(:)
    integer :: k, b, c
    do k = 1, loads%n_bounded
      c = first + k
      col_lo(c) = loads%bounded_lo_n(k)/scale_n
      col_hi(c) = loads%bounded_hi_n(k)/scale_n
      if (col_hi(c) <= col_lo(c)) col_kind(c) = lp_fixed
      b = loads%bounded_body(k)
      if (row_of(b) == 0) cycle
      ia(ne + 1:ne + 3) = row_of(b) + [0, 1, 2]
      ja(ne + 1:ne + 3) = c
      ar(ne + 1:ne + 3) = [loads%bounded_dir(:, k), cross2(loads%bounded_xy(:, k) - loads%centroid(:, b), &
                                                           loads%bounded_dir(:, k))]
      ne = ne + 3
    end do
  end subroutine bounded_columns

  !> The non-associative capacity (Gilbert, Casapulla and Ahmed 2006): Coulomb friction
  !> without dilatancy. Each step replaces the friction of every interface by a fixed
  !> shear limit mu N from the normal forces of the step before (starting from the
  !> associative solution `assoc`) and solves again, until lambda and the normal forces
  !> no longer change (1e-9 relative). After 20 steps the limit moves half-way only,
  !> which damps the oscillations the procedure can fall into.
  subroutine nonassociative_capacity(asm, faces, loads, friction, assoc, res, steps, converged, status)
    type(assembly_t), intent(in) :: asm
    type(interface_set_t), intent(in) :: faces
    type(block_loads_t), intent(in) :: loads
    real(dp), intent(in) :: friction(:)
    type(lp_result_t), intent(in) :: assoc
    type(lp_result_t), intent(out) :: res
    integer, intent(out) :: steps
    logical, intent(out) :: converged
    type(status_t), intent(inout) :: status
    integer, parameter :: max_steps = 200
    real(dp), parameter :: rel_tol = 1.0e-9_dp
    real(dp) :: normal(faces%n), limit(faces%n), previous_lambda, zero(faces%n), alpha
    zero = 0.0_dp
    normal = sum(assoc%normal_n, dim=1)
    limit = friction*normal
    previous_lambda = assoc%load_factor
    converged = .false.
    do steps = 1, max_steps
      call lp_capacity(asm, faces, loads, zero, limit, res, status)
      if (.not. status%ok) return
      normal = sum(res%normal_n, dim=1)
      if (abs(res%load_factor - previous_lambda) <= rel_tol*max(1.0_dp, abs(res%load_factor)) .and. &
          all(abs(friction*normal - limit) <= rel_tol*max(maxval([0.0_dp, limit]), tiny(1.0_dp)))) then
        converged = .true.
        return
      end if
      alpha = merge(1.0_dp, 0.5_dp, steps <= 20)
      limit = (1.0_dp - alpha)*limit + alpha*friction*normal
      previous_lambda = res%load_factor
    end do
    steps = max_steps
  end subroutine nonassociative_capacity

  !> The refusal of an unbounded problem, naming the free block of the interface whose
  !> force grows along GLPK's unbounded ray (column `ray`) where there is one, else the
  !> free blocks that carry the live load.
  pure subroutine refuse_unbounded(asm, faces, loads, ray, n_cols, res, status)
    type(assembly_t), intent(in) :: asm
    type(interface_set_t), intent(in) :: faces
    type(block_loads_t), intent(in) :: loads
    integer, intent(in) :: ray, n_cols
    type(lp_result_t), intent(inout) :: res
    type(status_t), intent(inout) :: status
    character(len=*), parameter :: what = 'no mechanism opens under the live load: lambda grows without bound '// &
                                          '(the linear programme is unbounded)'
    character(len=:), allocatable :: blocks
    integer :: k, b, n_loaded
    if (ray > 0 .and. ray < n_cols) then
      k = (ray + 2)/3
      res%unbounded_body = merge(faces%body(2, k), faces%body(1, k), asm%driven(faces%body(1, k)))
      call fail(status, what//'; block '//itoa(res%unbounded_body)//' is held against the load')
      return
    end if
    blocks = ''
    n_loaded = 0
    do b = 1, asm%n_bodies
      if (asm%driven(b) .or. (all(loads%live_n(:, b) == 0.0_dp) .and. loads%live_moment_nm(b) == 0.0_dp)) cycle
      n_loaded = n_loaded + 1
      if (res%unbounded_body == 0) res%unbounded_body = b
      if (n_loaded <= 5) blocks = blocks//merge(', ', '  ', n_loaded > 1)//itoa(b)
    end do
    blocks = adjustl(blocks)
    if (n_loaded == 0) then
      call fail(status, what//'; the live load acts on no free block (only on the supports)')
    else if (n_loaded <= 5) then
      call fail(status, what//'; the live load on block'//trim(merge('s ', '  ', n_loaded > 1))//' '//trim(blocks)// &
                ' is held by the blocks around '//trim(merge('them', 'it  ', n_loaded > 1)))
    else
      call fail(status, what//'; the live load acts on '//itoa(n_loaded)//' blocks (blocks '//trim(blocks)//', ...)')
    end if
  end subroutine refuse_unbounded

  !> The equilibrium coefficients of the columns N1, N2, S of interface k: on body(2) the
  !> force itself, on body(1) its opposite; moments about each block's centroid.
  pure subroutine interface_columns(faces, k, centroid, row_of, ia, ja, ar, ne)
    type(interface_set_t), intent(in) :: faces
    integer, intent(in) :: k, row_of(:)
    real(dp), intent(in) :: centroid(:, :)
    integer, intent(inout) :: ia(:), ja(:), ne
    real(dp), intent(inout) :: ar(:)
    real(dp) :: n(2), t(2), p(2), dir(2), sgn
    integer :: s, e, b, col
    n = faces%normal(:, k)
    t = [-n(2), n(1)]
    do s = 1, 2
      b = faces%body(s, k)
      if (row_of(b) == 0) cycle
      sgn = merge(-1.0_dp, 1.0_dp, s == 1)
      do e = 1, 3
        if (e < 3) then
          p = faces%end_xy(:, e, k)
          dir = n
        else
          p = 0.5_dp*(faces%end_xy(:, 1, k) + faces%end_xy(:, 2, k))
          dir = t
        end if
        col = 3*k - 3 + e
        ia(ne + 1:ne + 3) = row_of(b) + [0, 1, 2]
        ja(ne + 1:ne + 3) = col
        ar(ne + 1:ne + 3) = sgn*[dir(1), dir(2), cross2(p - centroid(:, b), dir)]
        ne = ne + 3
      end do
    end do
  end subroutine interface_columns

  !> The duals of the equilibrium rows are the velocities (u_x, u_y, omega) of the free
  !> blocks; driven blocks stay still. Scaled so that the live load's power is +1.
  pure subroutine velocities_from_duals(asm, loads, row_of, dual, velocity)
    type(assembly_t), intent(in) :: asm
    type(block_loads_t), intent(in) :: loads
    integer, intent(in) :: row_of(:)
    real(dp), intent(in) :: dual(:)
    real(dp), allocatable, intent(out) :: velocity(:, :)
    real(dp) :: power
    integer :: b
    allocate (velocity(3, asm%n_bodies))
    velocity = 0.0_dp
    do b = 1, asm%n_bodies
      if (row_of(b) > 0) velocity(:, b) = dual(row_of(b):row_of(b) + 2)
    end do
    power = sum(loads%live_n(1, :)*velocity(1, :) + loads%live_n(2, :)*velocity(2, :) + &
                loads%live_moment_nm*velocity(3, :))
    if (power /= 0.0_dp) velocity = velocity/power
  end subroutine velocities_from_duals

  !> Velocity of the point p of a block moving with v = (u_x, u_y, omega) about centroid c.
  pure function point_velocity(v, c, p) result(w)
    real(dp), intent(in) :: v(3), c(2), p(2)
    real(dp) :: w(2)
    w = [v(1) - v(3)*(p(2) - c(2)), v(2) + v(3)*(p(1) - c(1))]
  end function point_velocity

  !> Opening of each end and sliding of interface k: the velocity of body(2) relative to
  !> body(1), along the normal at each end and along the tangent.
  pure subroutine joint_motion(faces, k, centroid, velocity, opening, slip)
    type(interface_set_t), intent(in) :: faces
    integer, intent(in) :: k
    real(dp), intent(in) :: centroid(:, :), velocity(:, :)
    real(dp), intent(out) :: opening(2), slip
    real(dp) :: rel(2), n(2)
    integer :: e, a, b
    a = faces%body(1, k)
    b = faces%body(2, k)
    n = faces%normal(:, k)
    do e = 1, 2
      rel = point_velocity(velocity(:, b), centroid(:, b), faces%end_xy(:, e, k)) - &
            point_velocity(velocity(:, a), centroid(:, a), faces%end_xy(:, e, k))
      opening(e) = dot_product(rel, n)
      if (e == 1) slip = dot_product(rel, [-n(2), n(1)])
    end do
  end subroutine joint_motion

  !> Each interface closed, hinging about one end, sliding, or open; motions below 1e-6
  !> of the largest relative motion count as none.
  pure subroutine classify_joints(faces, centroid, velocity, mode, pivot_end)
    type(interface_set_t), intent(in) :: faces
    real(dp), intent(in) :: centroid(:, :), velocity(:, :)
    integer, allocatable, intent(out) :: mode(:), pivot_end(:)
    real(dp) :: opening(2, faces%n), slip(faces%n), tol
    integer :: k
    allocate (mode(faces%n), pivot_end(faces%n))
    do k = 1, faces%n
      call joint_motion(faces, k, centroid, velocity, opening(:, k), slip(k))
    end do
    tol = 1.0e-6_dp*max(maxval([0.0_dp, abs(slip)]), maxval([0.0_dp, abs(opening(1, :)), abs(opening(2, :))]), &
                        tiny(1.0_dp))
    pivot_end = 0
    do k = 1, faces%n
      if (abs(slip(k)) > tol) then
        mode(k) = joint_sliding
      else if (opening(1, k) > tol .and. opening(2, k) > tol) then
        mode(k) = joint_open
      else if (opening(1, k) > tol) then
        mode(k) = joint_hinge
        pivot_end(k) = 2
      else if (opening(2, k) > tol) then
        mode(k) = joint_hinge
        pivot_end(k) = 1
      else
        mode(k) = joint_closed
      end if
    end do
  end subroutine classify_joints

  !> The upper bound: lambda of the mechanism by the work equation, the live load's
  !> power being 1: lambda = dissipation - power of the dead load (weights and dead
  !> point loads) - power of the bounded forces. Coulomb with dilatancy dissipates nothing;
  !> a fixed shear limit c dissipates c |slip|.
  pure real(dp) function work_load_factor(faces, loads, velocity, cohesion_n) result(lambda)
    type(interface_set_t), intent(in) :: faces
    type(block_loads_t), intent(in) :: loads
    real(dp), intent(in) :: velocity(:, :), cohesion_n(:)
    real(dp) :: opening(2), slip, dissipation, rate
    integer :: k
    dissipation = 0.0_dp
    do k = 1, faces%n
      call joint_motion(faces, k, loads%centroid, velocity, opening, slip)
      dissipation = dissipation + cohesion_n(k)*abs(slip)
    end do
    lambda = dissipation - sum(loads%dead_n(1, :)*velocity(1, :) + (loads%dead_n(2, :) - loads%weight_n)*velocity(2, :) &
                               + loads%dead_moment_nm*velocity(3, :))
    ! A bounded force resists with its upper bound where its point moves against it (the ring
    ! into the fill: passive) and pushes with its lower bound where it moves with it (active).
    do k = 1, loads%n_bounded
      rate = dot_product(loads%bounded_dir(:, k), point_velocity(velocity(:, loads%bounded_body(k)), &
                         loads%centroid(:, loads%bounded_body(k)), loads%bounded_xy(:, k)))
      lambda = lambda - merge(loads%bounded_hi_n(k), loads%bounded_lo_n(k), rate < 0.0_dp)*rate
    end do
  end function work_load_factor

  !> 'closed', 'hinge', 'sliding' or 'open'.
  pure function joint_mode_name(mode) result(name)
    integer, intent(in) :: mode
    character(len=:), allocatable :: name
    select case (mode)
    case (joint_hinge)
      name = 'hinge'
    case (joint_sliding)
      name = 'sliding'
    case (joint_open)
      name = 'open'
    case default
      name = 'closed'
    end select
  end function joint_mode_name

end module voussoir_limit_lp
