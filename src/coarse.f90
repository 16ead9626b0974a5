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
  use voussoir_contact_rows, only: i_t, i_n, i_arm_at, i_arm_an, i_arm_bt, i_arm_bn, i_shift, i_mu, &
                                   i_ima, i_iia, i_imb, i_iib, n_rows
  implicit none
  private

  public :: coarse_t, coarse_init, coarse_correct

  !> Sweeps between two coarse corrections (the first follows the first sweep).
  integer, parameter, public :: coarse_period = 8
  !> Coarse unknowns per bed joint (the patterns 1 to 3 above).
  integer, parameter :: n_modes = 3
  !> Aggregates one body may touch (segments of the joints below and above it: two of
  !> each when a segment is at least twice as wide as a block).
  integer, parameter :: max_groups = 4
  !> An unloaded contact opens when its normal velocity exceeds this fraction of the
  !> largest body speed (below it, the velocity is round-off of touching faces).
  real(dp), parameter :: opening_fraction = 1.0e-6_dp

  !> The aggregates of a wall and the work arrays of the coarse solve.
  type :: coarse_t
    integer :: n_joints = 0                 !! bed joints; 0: no correction
    integer :: n_segments = 1               !! aggregates per bed joint (segments along the wall)
    integer :: period = coarse_period       !! sweeps between two corrections
    integer, allocatable :: course(:)       !! (n_bodies) course of each body, 0 the foundation, -1 none
    real(dp), allocatable :: inv_mass(:), inv_inertia(:)  !! (n_bodies) [1/kg], [1/(kg m2)]
    !> (n_bodies) aggregates a body touches, (max_groups, n_bodies) the first unknown
    !> (less 1) of each, and (3, max_groups n_modes, n_bodies) the generalised force on
    !> the body of a unit value of each unknown
    integer, allocatable :: n_slots(:), slot(:, :)
    real(dp), allocatable :: force(:, :, :)
    real(dp), allocatable :: band(:, :)     !! (kd + 1, n_unknowns) P^T W P, LAPACK upper band storage
    real(dp), allocatable :: delta(:)       !! (n_unknowns) right-hand side, then the correction
    ! Per contact: its aggregate's first unknown (0: none), and P: the weights of the shear and moment patterns.
    integer, allocatable :: joint(:)
    real(dp), allocatable :: shear(:), moment(:)
  end type coarse_t

contains

  !> Aggregates from the course of every body (0 the foundation, -1 a body outside the
  !> courses); `inv_mass` and `inv_inertia` are 0 for driven bodies. With `segment` > 0,
  !> each bed joint is split along the wall into segments of about `segment` blocks (of
  !> the course with the fewest bodies), each an aggregate with its own `n_modes` unknowns;
  !> 0 or absent: one aggregate per bed joint.
  subroutine coarse_init(coarse, course, inv_mass, inv_inertia, segment)
    type(coarse_t), intent(out) :: coarse
    integer, intent(in) :: course(:)
    real(dp), intent(in) :: inv_mass(:), inv_inertia(:)
    integer, intent(in), optional :: segment
    integer :: n_unknowns, j, fewest
    coarse%course = course
    coarse%inv_mass = inv_mass
    coarse%inv_inertia = inv_inertia
    coarse%n_joints = max(0, maxval(course))
    coarse%n_segments = 1
    if (present(segment) .and. coarse%n_joints > 0) then
      if (segment > 0) then
        fewest = huge(1)
        do j = 1, coarse%n_joints
          fewest = min(fewest, count(course == j))
        end do
        coarse%n_segments = max(1, nint(real(fewest, dp)/segment))
      end if
    end if
    n_unknowns = max(1, coarse%n_joints*coarse%n_segments*n_modes)
    allocate (coarse%n_slots(size(course)), coarse%slot(max_groups, size(course)), &
              coarse%force(3, max_groups*n_modes, size(course)), &
              coarse%band(n_modes*(coarse%n_segments + 2), n_unknowns), coarse%delta(n_unknowns))
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
    integer :: kd   ! band width of P^T W P
    integer :: k, a, b, j, p, q, m, g, h, course_a, course_b, info, n_unknowns, n_seg, s, row, col, ga, gb, lo, hi
    real(dp) :: u_t, u_n, r_t, r_n, dr_t, dr_n, px, py, im, ii, x_min, x_max, x_mid, x_half, shear, moment, opening
    real(dp) :: seg_w, seg_mid, seg_half, fx, fy, fr
    real(dp) :: fa(3, n_modes), fb(3, n_modes)

    n_seg = coarse%n_segments
    n_unknowns = coarse%n_joints*n_seg*n_modes
    if (n_unknowns == 0 .or. n == 0) return
    if (allocated(coarse%joint)) then
      if (size(coarse%joint) < n) deallocate (coarse%joint, coarse%shear, coarse%moment)
    end if
    if (.not. allocated(coarse%joint)) &
      allocate (coarse%joint(max(64, 2*n)), coarse%shear(max(64, 2*n)), coarse%moment(max(64, 2*n)))
    ! The moment pattern's abscissa runs from -1 to 1 over the contacts of a segment (the
    ! extreme abscissae in one pass: the first of equal values, as maxval and minval take them).
    x_max = point(1, 1)
    x_min = point(1, 1)
    do k = 2, n
      if (point(1, k) > x_max) x_max = point(1, k)
      if (point(1, k) < x_min) x_min = point(1, k)
    end do
    x_mid = 0.5_dp*(x_max + x_min)
    x_half = max(0.5_dp*(x_max - x_min), tiny(1.0_dp))
    seg_w = 2.0_dp*x_half/n_seg
    seg_half = x_half/n_seg
    opening = opening_fraction*maxval(abs(v(1:2, :)))

    ! Restriction: P^T u, and P^T H^T body by body (the generalised force of each unknown).
    coarse%n_slots = 0
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
      ! Patterns: (0, 1) weight; (shear, 0) a push along +x on the upper course, whichever
      ! of a and b it is; (0, moment) the linear normal addition over the segment.
      shear = sign(1.0_dp, c(i_t, k))
      if (course_a /= j) shear = -shear
      if (n_seg == 1) then
        s = 0
        moment = (point(1, k) - x_mid)/x_half
      else
        s = min(n_seg - 1, max(0, int((point(1, k) - x_min)/seg_w)))
        seg_mid = x_min + (s + 0.5_dp)*seg_w
        moment = (point(1, k) - seg_mid)/seg_half
      end if
      p = ((j - 1)*n_seg + s)*n_modes
      ga = find_slot(a, p)
      gb = find_slot(b, p)
      if (ga == 0 .or. gb == 0) return   ! more aggregates on a body than foreseen: no correction
      coarse%joint(k) = p + 1
      coarse%shear(k) = shear
      coarse%moment(k) = moment
      coarse%delta(p + 1) = coarse%delta(p + 1) - u_n
      coarse%delta(p + 2) = coarse%delta(p + 2) - shear*u_t
      coarse%delta(p + 3) = coarse%delta(p + 3) - moment*u_n
      fa(:, 1) = [c(i_n, k), c(i_n + 1, k), c(i_arm_an, k)]
      fa(:, 2) = shear*[c(i_t, k), c(i_t + 1, k), c(i_arm_at, k)]
      fa(:, 3) = moment*fa(:, 1)
      fb(:, 1) = [c(i_n, k), c(i_n + 1, k), c(i_arm_bn, k)]
      fb(:, 2) = shear*[c(i_t, k), c(i_t + 1, k), c(i_arm_bt, k)]
      fb(:, 3) = moment*fb(:, 1)
      if (ga > 0) then
        ga = (ga - 1)*n_modes
        coarse%force(:, ga + 1:ga + n_modes, a) = coarse%force(:, ga + 1:ga + n_modes, a) + fa
      end if
      if (gb > 0) then
        gb = (gb - 1)*n_modes
        coarse%force(:, gb + 1:gb + n_modes, b) = coarse%force(:, gb + 1:gb + n_modes, b) - fb
      end if
    end do

    ! Band width: the widest span of unknowns on one body.
    kd = n_modes - 1
    do b = 1, n_bodies
      if (coarse%n_slots(b) < 2 .or. coarse%course(b) < 0 .or. coarse%inv_mass(b) == 0.0_dp) cycle
      lo = minval(coarse%slot(1:coarse%n_slots(b), b))
      hi = maxval(coarse%slot(1:coarse%n_slots(b), b))
      kd = max(kd, hi - lo + n_modes - 1)
    end do
    if (size(coarse%band, 1) < kd + 1) then
      deallocate (coarse%band)
      allocate (coarse%band(kd + 1, n_unknowns))
    end if

    ! Galerkin operator P^T W P = sum over bodies of F^T M^-1 F, banded.
    coarse%band(1:kd + 1, 1:n_unknowns) = 0.0_dp
    do b = 1, n_bodies
      im = coarse%inv_mass(b)
      ii = coarse%inv_inertia(b)
      if (coarse%course(b) < 0 .or. im == 0.0_dp) cycle
      do h = 1, coarse%n_slots(b)
        do g = 1, coarse%n_slots(b)
          if (coarse%slot(g, b) > coarse%slot(h, b)) cycle   ! the upper triangle only
          do q = 1, n_modes
            col = coarse%slot(h, b) + q
            fx = im*coarse%force(1, (h - 1)*n_modes + q, b)
            fy = im*coarse%force(2, (h - 1)*n_modes + q, b)
            fr = ii*coarse%force(3, (h - 1)*n_modes + q, b)
            do m = 1, n_modes
              row = coarse%slot(g, b) + m
              if (row > col) exit
              associate (gg => coarse%force(:, (g - 1)*n_modes + m, b))
                coarse%band(kd + 1 + row - col, col) = coarse%band(kd + 1 + row - col, col) &
                  + (fx*gg(1) + fy*gg(2)) + fr*gg(3)
              end associate
            end do
          end do
        end do
      end do
    end do
    ! An unknown without active contacts: delta = 0 there.
    do p = 1, n_unknowns
      if (coarse%band(kd + 1, p) <= 0.0_dp) then
        coarse%band(kd + 1, p) = 1.0_dp
        coarse%delta(p) = 0.0_dp
      end if
    end do
    call dpbtrf('U', n_unknowns, kd, coarse%band, size(coarse%band, 1), info)
    if (info /= 0) return   ! not positive definite (a degenerate contact set): no correction
    call dpbtrs('U', n_unknowns, kd, 1, coarse%band, size(coarse%band, 1), coarse%delta, n_unknowns, info)
    if (info /= 0) return

    ! Prolongation, projection on the cone, and the velocities of the change made.
    do k = 1, n
      p = coarse%joint(k) - 1
      if (p < 0) cycle
      a = pair(1, k)
      b = pair(2, k)
      r_n = max(0.0_dp, r(2, k) + coarse%delta(p + 1) + coarse%moment(k)*coarse%delta(p + 3))
      r_t = max(-c(i_mu, k)*r_n, min(c(i_mu, k)*r_n, r(1, k) + coarse%shear(k)*coarse%delta(p + 2)))
      dr_t = r_t - r(1, k)
      dr_n = r_n - r(2, k)
      r(1, k) = r_t
      r(2, k) = r_n
      px = dr_t*c(i_t, k) + dr_n*c(i_n, k)
      py = dr_t*c(i_t + 1, k) + dr_n*c(i_n + 1, k)
      v(1, a) = v(1, a) + c(i_ima, k)*px
      v(2, a) = v(2, a) + c(i_ima, k)*py
      v(3, a) = v(3, a) + c(i_iia, k)*(dr_t*c(i_arm_at, k) + dr_n*c(i_arm_an, k))
      v(1, b) = v(1, b) - c(i_imb, k)*px
      v(2, b) = v(2, b) - c(i_imb, k)*py
      v(3, b) = v(3, b) - c(i_iib, k)*(dr_t*c(i_arm_bt, k) + dr_n*c(i_arm_bn, k))
    end do

  contains

    !> The slot of the unknowns from `base` + 1 on body `body` (a new one, its force zeroed,
    !> if the body has none yet); -1 for a driven body (no force needed), 0 when the body
    !> has `max_groups` already.
    integer function find_slot(body, base) result(found)
      integer, intent(in) :: body, base
      integer :: i
      found = -1
      if (coarse%inv_mass(body) == 0.0_dp) return
      do i = 1, coarse%n_slots(body)
        if (coarse%slot(i, body) == base) then
          found = i
          return
        end if
      end do
      found = 0
      if (coarse%n_slots(body) == max_groups) return
      found = coarse%n_slots(body) + 1
      coarse%n_slots(body) = found
      coarse%slot(found, body) = base
      coarse%force(:, (found - 1)*n_modes + 1:found*n_modes, body) = 0.0_dp
    end function find_slot
  end subroutine coarse_correct

end module voussoir_coarse
