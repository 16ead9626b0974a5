!> Two-level (aggregation) correction of the impulses of a wall, bed joint by bed joint.
!>
!> Gauss-Seidel carries the weight of a stack of courses down by one course per sweep
!> (and the shear of the shaken courses above likewise), so a tall wall needs as many
!> sweeps as it has courses to settle, and its "converged" impulses can keep a large
!> error per course that one sweep barely changes. The coarse level has `n_modes`
!> unknowns per bed joint j (between course j - 1 and course j), each a pattern added to
!> the impulses of the joint's active contacts (the prolongation P):
!>   1. a uniform addition to the normal impulses (the weight carried),
!>   2. a uniform horizontal push on the upper course through the tangential impulses
!>      (the shear carried),
!>   3. a normal addition growing linearly along the wall (the overturning moment).
!> The correction delta solves the Galerkin system (P^T W P) delta = -P^T u, W = H M^-1 H^T
!> the Delassus operator and u the present relative velocities (gap shift included):
!> the exact minimiser of the linear problem's energy over the coarse space. A block
!> touches only the joint below and the joint above, so P^T W P is banded (band width
!> 2 n_modes - 1), symmetric and positive definite; LAPACK's banded Cholesky (dpbtrf,
!> dpbtrs) solves it. The corrected impulses are projected back on the Coulomb cone
!> (r_n >= 0, |r_t| <= mu r_n) and the velocities updated with the change actually made,
!> so v = v_free + M^-1 H^T r holds and the sweeps converge to the same solution.
module voussoir_coarse
  use voussoir_kinds, only: dp
  use voussoir_contact_rows, only: i_t, i_n, i_arm_at, i_arm_an, i_arm_bt, i_arm_bn, i_shift, i_mu, n_rows, &
                                   apply_impulse_change
  implicit none
  private

  public :: coarse_t, coarse_init, coarse_correct

  !> Sweeps between two coarse corrections (the first follows the first sweep).
  integer, parameter, public :: coarse_period = 8
  !> No correction after this many sweeps of one step: where the projection on the cone
  !> and the sweeps undo each other (a wall sliding on its foundation), the plain sweeps
  !> then converge as without the correction (the corrections only shorten the way).
  integer, parameter, public :: coarse_last_sweep = 64
  !> Coarse unknowns per bed joint (the patterns 1 to 3 above).
  integer, parameter :: n_modes = 3
  !> Band width of P^T W P (superdiagonals).
  integer, parameter :: kd = 2*n_modes - 1
  !> An unloaded contact opens when its normal velocity exceeds this fraction of the
  !> largest body speed (below it, the velocity is round-off of touching faces).
  real(dp), parameter :: opening_fraction = 1.0e-6_dp

  !> The aggregates of a wall and the work arrays of the coarse solve.
  type :: coarse_t
    integer :: n_joints = 0                 !! bed joints; 0: no correction
    integer, allocatable :: course(:)       !! (n_bodies) course of each body, 0 the foundation, -1 none
    real(dp), allocatable :: inv_mass(:), inv_inertia(:)  !! (n_bodies) [1/kg], [1/(kg m2)]
    !> (3, 2 n_modes, n_bodies) generalised force on a body of a unit coarse unknown of the
    !> joint below (1 : n_modes) and of the joint above (n_modes + 1 : 2 n_modes)
    real(dp), allocatable :: force(:, :, :)
    real(dp), allocatable :: band(:, :)     !! (2 n_modes, n_joints n_modes) P^T W P, LAPACK upper band storage
    real(dp), allocatable :: delta(:)       !! (n_joints n_modes) right-hand side, then the correction
    ! Per contact: its bed joint (0: none), and P: the weights of the shear and moment patterns.
    integer, allocatable :: joint(:)
    real(dp), allocatable :: shear(:), moment(:)
  end type coarse_t

contains

  !> Aggregates from the course of every body (0 the foundation, -1 a body outside the
  !> courses); `inv_mass` and `inv_inertia` are 0 for driven bodies.
  subroutine coarse_init(coarse, course, inv_mass, inv_inertia)
    type(coarse_t), intent(out) :: coarse
    integer, intent(in) :: course(:)
    real(dp), intent(in) :: inv_mass(:), inv_inertia(:)
    integer :: n_unknowns
    coarse%course = course
    coarse%inv_mass = inv_mass
    coarse%inv_inertia = inv_inertia
    coarse%n_joints = max(0, maxval(course))
    n_unknowns = max(1, coarse%n_joints*n_modes)
    allocate (coarse%force(3, 2*n_modes, size(course)), coarse%band(2*n_modes, n_unknowns), coarse%delta(n_unknowns))
  end subroutine coarse_init

  !> One coarse correction of the impulses `r` (2, n) of the contacts described by `pair`,
  !> the packed data `c` and the contact points `point` (2, n) [m], with the velocities
  !> `v` (3, n_bodies) kept consistent. A contact takes part when it joins two
  !> neighbouring courses and is active (it carries an impulse or is not opening); the
  !> others are left to the sweeps.
  subroutine coarse_correct(coarse, n, n_bodies, pair, c, point, r, v)
    type(coarse_t), intent(inout) :: coarse
    integer, intent(in) :: n, n_bodies
    integer, intent(in) :: pair(2, n)
    real(dp), intent(in) :: c(n_rows, n), point(2, n)
    real(dp), intent(inout) :: r(2, n), v(3, n_bodies)
    integer :: info, n_unknowns

    n_unknowns = coarse%n_joints*n_modes
    if (n_unknowns == 0 .or. n == 0) return
    if (allocated(coarse%joint)) then
      if (size(coarse%joint) < n) deallocate (coarse%joint, coarse%shear, coarse%moment)
    end if
    if (.not. allocated(coarse%joint)) &
      allocate (coarse%joint(max(64, 2*n)), coarse%shear(max(64, 2*n)), coarse%moment(max(64, 2*n)))
    call restrict(coarse, n, n_bodies, pair, c, point, r, v, n_unknowns)
    call assemble_galerkin(coarse, n_bodies, n_unknowns)
    call dpbtrf('U', n_unknowns, kd, coarse%band, kd + 1, info)
    if (info /= 0) return   ! not positive definite (a degenerate contact set): no correction
    call dpbtrs('U', n_unknowns, kd, 1, coarse%band, kd + 1, coarse%delta, n_unknowns, info)
    if (info /= 0) return
    call prolong(coarse, n, n_bodies, pair, c, r, v)
  end subroutine coarse_correct

  !> Restriction: the right-hand side -P^T u in `coarse%delta`, the generalised force of
  !> each unknown on each body (P^T H^T) in `coarse%force`, and per contact its bed joint
  !> (0: not taking part) and its pattern weights.
  subroutine restrict(coarse, n, n_bodies, pair, c, point, r, v, n_unknowns)
    type(coarse_t), intent(inout) :: coarse
    integer, intent(in) :: n, n_bodies, n_unknowns
    integer, intent(in) :: pair(2, n)
    real(dp), intent(in) :: c(n_rows, n), point(2, n), r(2, n), v(3, n_bodies)
    integer :: k, a, b, j, p, course_a, course_b, slot_a, slot_b
    real(dp) :: u_t, u_n, x_min, x_max, x_mid, x_half, shear, moment, opening
    real(dp) :: fa(3, n_modes), fb(3, n_modes)

    ! The moment pattern's abscissa runs from -1 to 1 over the contacts (the extreme
    ! abscissae in one pass: the first of equal values, as maxval and minval take them).
    x_max = point(1, 1)
    x_min = point(1, 1)
    do k = 2, n
      if (point(1, k) > x_max) x_max = point(1, k)
      if (point(1, k) < x_min) x_min = point(1, k)
    end do
    x_mid = 0.5_dp*(x_max + x_min)
    x_half = max(0.5_dp*(x_max - x_min), tiny(1.0_dp))
    opening = opening_fraction*maxval(abs(v(1:2, :)))

    coarse%force = 0.0_dp
    coarse%delta(1:n_unknowns) = 0.0_dp
    do k = 1, n
      coarse%joint(k) = 0
      a = pair(1, k)
      b = pair(2, k)
      course_a = coarse%course(a)
      course_b = coarse%course(b)
      if (course_a < 0 .or. course_b < 0 .or. abs(course_a - course_b) /= 1) cycle
      u_n = c(i_n, k)*(v(1, a) - v(1, b)) + c(i_n + 1, k)*(v(2, a) - v(2, b)) &
            + c(i_arm_an, k)*v(3, a) - c(i_arm_bn, k)*v(3, b) + c(i_shift, k)
      if (r(2, k) <= 0.0_dp .and. u_n > opening) cycle   ! opening: not part of the load path
      u_t = c(i_t, k)*(v(1, a) - v(1, b)) + c(i_t + 1, k)*(v(2, a) - v(2, b)) &
            + c(i_arm_at, k)*v(3, a) - c(i_arm_bt, k)*v(3, b)
      j = max(course_a, course_b)
      coarse%joint(k) = j
      ! Patterns: (0, 1) weight; (shear, 0) a push along +x on the upper course, whichever
      ! of a and b it is; (0, moment) the linear normal addition.
      shear = sign(1.0_dp, c(i_t, k))
      if (course_a /= j) shear = -shear
      moment = (point(1, k) - x_mid)/x_half
      coarse%shear(k) = shear
      coarse%moment(k) = moment
      p = (j - 1)*n_modes
      coarse%delta(p + 1) = coarse%delta(p + 1) - u_n
      coarse%delta(p + 2) = coarse%delta(p + 2) - shear*u_t
      coarse%delta(p + 3) = coarse%delta(p + 3) - moment*u_n
      fa(:, 1) = [c(i_n, k), c(i_n + 1, k), c(i_arm_an, k)]
      fa(:, 2) = shear*[c(i_t, k), c(i_t + 1, k), c(i_arm_at, k)]
      fa(:, 3) = moment*fa(:, 1)
      fb(:, 1) = [c(i_n, k), c(i_n + 1, k), c(i_arm_bn, k)]
      fb(:, 2) = shear*[c(i_t, k), c(i_t + 1, k), c(i_arm_bt, k)]
      fb(:, 3) = moment*fb(:, 1)
      ! Joint j is below the body of course j (slots 1 : 3) and above that of course j - 1.
      slot_a = merge(0, n_modes, course_a == j)
      slot_b = merge(0, n_modes, course_b == j)
      coarse%force(:, slot_a + 1:slot_a + n_modes, a) = coarse%force(:, slot_a + 1:slot_a + n_modes, a) + fa
      coarse%force(:, slot_b + 1:slot_b + n_modes, b) = coarse%force(:, slot_b + 1:slot_b + n_modes, b) - fb
    end do
  end subroutine restrict

  !> The Galerkin operator P^T W P = sum over bodies of F^T M^-1 F, banded in the joint,
  !> into `coarse%band`; an unknown without active contacts gets delta = 0.
  subroutine assemble_galerkin(coarse, n_bodies, n_unknowns)
    type(coarse_t), intent(inout) :: coarse
    integer, intent(in) :: n_bodies, n_unknowns
    integer :: b, j, p, q, row, col
    real(dp) :: im, ii

    coarse%band(:, 1:n_unknowns) = 0.0_dp
    do b = 1, n_bodies
      j = coarse%course(b)
      im = coarse%inv_mass(b)
      ii = coarse%inv_inertia(b)
      if (j < 0 .or. im == 0.0_dp) cycle
      ! Slot s of the body is unknown (j - 1) n_modes + s (joint below, then joint above).
      do q = 1, 2*n_modes
        col = (j - 1)*n_modes + q
        if (col < 1 .or. col > n_unknowns) cycle
        do p = max(1, 1 - (j - 1)*n_modes), q
          row = (j - 1)*n_modes + p
          associate (f => coarse%force(:, q, b), g => coarse%force(:, p, b))
            coarse%band(kd + 1 + row - col, col) = coarse%band(kd + 1 + row - col, col) &
              + im*(f(1)*g(1) + f(2)*g(2)) + ii*f(3)*g(3)
          end associate
        end do
      end do
    end do
    do p = 1, n_unknowns
      if (coarse%band(kd + 1, p) <= 0.0_dp) then
        coarse%band(kd + 1, p) = 1.0_dp
        coarse%delta(p) = 0.0_dp
      end if
    end do
  end subroutine assemble_galerkin

  !> Prolongation of the correction `coarse%delta`, projection on the cone, and the
  !> velocities of the change made.
  subroutine prolong(coarse, n, n_bodies, pair, c, r, v)
    type(coarse_t), intent(in) :: coarse
    integer, intent(in) :: n, n_bodies
    integer, intent(in) :: pair(2, n)
    real(dp), intent(in) :: c(n_rows, n)
    real(dp), intent(inout) :: r(2, n), v(3, n_bodies)
    integer :: k, a, b, j, p
    real(dp) :: r_t, r_n, dr_t, dr_n

    do k = 1, n
      j = coarse%joint(k)
      if (j == 0) cycle
      a = pair(1, k)
      b = pair(2, k)
      p = (j - 1)*n_modes
      r_n = max(0.0_dp, r(2, k) + coarse%delta(p + 1) + coarse%moment(k)*coarse%delta(p + 3))
      r_t = max(-c(i_mu, k)*r_n, min(c(i_mu, k)*r_n, r(1, k) + coarse%shear(k)*coarse%delta(p + 2)))
      dr_t = r_t - r(1, k)
      dr_n = r_n - r(2, k)
      r(1, k) = r_t
      r(2, k) = r_n
      call apply_impulse_change(c(:, k), dr_t, dr_n, v(:, a), v(:, b))
    end do
  end subroutine prolong

end module voussoir_coarse
