!> Non-linear Gauss-Seidel over contact points with the exact local Coulomb solve.
!>
!> The unknowns are the end-of-step velocities of the free bodies and the impulses of
!> the contacts. Each local problem u = u_free + W r, with W = H M^-1 H^T the 2 x 2
!> Delassus block of the contact, is solved exactly for the inelastic Signorini-Coulomb
!> law; then the velocities of its two bodies are updated, so no global matrix exists.
module voussoir_nlgs
  use voussoir_kinds, only: dp
  use voussoir_geometry, only: cross2
  use voussoir_bodies, only: bodies_t
  use voussoir_contacts, only: contact_set_t
  implicit none
  private

  public :: nlgs_work_t, nlgs_prepare, nlgs_solve, coulomb_local, warm_start

  !> Per-contact data of the solve: Delassus blocks, lever arms and the gap shift.
  type :: nlgs_work_t
    real(dp), allocatable :: w_tt(:), w_tn(:), w_nn(:), det(:)
    real(dp), allocatable :: arm_at(:), arm_an(:), arm_bt(:), arm_bn(:) !! cross(arm, t or n)
    real(dp), allocatable :: shift(:)  !! max(0, gap)/(theta h) [m/s]
    ! Warm start: the previous step's contacts sorted by candidate body.
    integer :: n_prev = 0
    integer, allocatable :: prev_first(:), prev_b(:), prev_slot(:)
    real(dp), allocatable :: prev_impulse(:, :)
  end type nlgs_work_t

contains

  !> Delassus blocks, lever-arm products and gap shifts of every contact.
  subroutine nlgs_prepare(bodies, set, h_theta_s, work)
    type(bodies_t), intent(in) :: bodies
    type(contact_set_t), intent(in) :: set
    real(dp), intent(in) :: h_theta_s   !! theta times the time step [s]
    type(nlgs_work_t), intent(inout) :: work
    integer :: k, a, b, cap

    cap = max(set%n, 1)
    if (allocated(work%w_tt)) then
      if (size(work%w_tt) < cap) deallocate (work%w_tt, work%w_tn, work%w_nn, work%det, &
                                             work%arm_at, work%arm_an, work%arm_bt, &
                                             work%arm_bn, work%shift)
    end if
    if (.not. allocated(work%w_tt)) then
      cap = max(2*cap, 64)
      allocate (work%w_tt(cap), work%w_tn(cap), work%w_nn(cap), work%det(cap), &
                work%arm_at(cap), work%arm_an(cap), work%arm_bt(cap), work%arm_bn(cap), &
                work%shift(cap))
    end if
    do k = 1, set%n
      a = set%body_a(k)
      b = set%body_b(k)
      work%arm_at(k) = cross2(set%arm_a(:, k), set%tangent(:, k))
      work%arm_an(k) = cross2(set%arm_a(:, k), set%normal(:, k))
      work%arm_bt(k) = cross2(set%arm_b(:, k), set%tangent(:, k))
      work%arm_bn(k) = cross2(set%arm_b(:, k), set%normal(:, k))
      work%w_tt(k) = bodies%inv_mass(a) + bodies%inv_inertia(a)*work%arm_at(k)**2 &
                     + bodies%inv_mass(b) + bodies%inv_inertia(b)*work%arm_bt(k)**2
      work%w_nn(k) = bodies%inv_mass(a) + bodies%inv_inertia(a)*work%arm_an(k)**2 &
                     + bodies%inv_mass(b) + bodies%inv_inertia(b)*work%arm_bn(k)**2
      work%w_tn(k) = bodies%inv_inertia(a)*work%arm_at(k)*work%arm_an(k) &
                     + bodies%inv_inertia(b)*work%arm_bt(k)*work%arm_bn(k)
      work%det(k) = work%w_tt(k)*work%w_nn(k) - work%w_tn(k)**2
      work%shift(k) = max(0.0_dp, set%gap_m(k))/h_theta_s
    end do
  end subroutine nlgs_prepare

  !> Take the impulses of the previous step's contacts that match (same bodies, same
  !> slot) as the first guess, then store the present set for the next step.
  subroutine warm_start(work, set, n_bodies, remember)
    type(nlgs_work_t), intent(inout) :: work
    type(contact_set_t), intent(inout) :: set
    integer, intent(in) :: n_bodies
    logical, intent(in) :: remember  !! false: only look up; true: only store
    integer :: k, m, a, pos

    if (.not. remember) then
      if (work%n_prev == 0 .or. .not. allocated(work%prev_first)) return
      if (size(work%prev_first) /= n_bodies + 1) return
      do k = 1, set%n
        a = set%body_a(k)
        do m = work%prev_first(a), work%prev_first(a + 1) - 1
          if (work%prev_b(m) == set%body_b(k) .and. work%prev_slot(m) == set%slot(k)) then
            set%impulse(:, k) = work%prev_impulse(:, m)
            exit
          end if
        end do
      end do
      return
    end if

    if (allocated(work%prev_first)) then
      if (size(work%prev_first) /= n_bodies + 1) deallocate (work%prev_first)
    end if
    if (.not. allocated(work%prev_first)) allocate (work%prev_first(n_bodies + 1))
    if (allocated(work%prev_b)) then
      if (size(work%prev_b) < set%n) deallocate (work%prev_b, work%prev_slot, work%prev_impulse)
    end if
    if (.not. allocated(work%prev_b)) then
      allocate (work%prev_b(max(64, 2*set%n)), work%prev_slot(max(64, 2*set%n)), &
                work%prev_impulse(2, max(64, 2*set%n)))
    end if
    ! Counting sort by candidate body.
    work%prev_first = 0
    do k = 1, set%n
      a = set%body_a(k)
      work%prev_first(a + 1) = work%prev_first(a + 1) + 1
    end do
    work%prev_first(1) = 1
    do a = 2, n_bodies + 1
      work%prev_first(a) = work%prev_first(a) + work%prev_first(a - 1)
    end do
    do k = set%n, 1, -1
      a = set%body_a(k)
      work%prev_first(a + 1) = work%prev_first(a + 1) - 1
      pos = work%prev_first(a + 1)
      work%prev_b(pos) = set%body_b(k)
      work%prev_slot(pos) = set%slot(k)
      work%prev_impulse(:, pos) = set%impulse(:, k)
    end do
    do a = 1, n_bodies
      work%prev_first(a) = work%prev_first(a + 1)
    end do
    work%prev_first(n_bodies + 1) = set%n + 1
    work%n_prev = set%n
  end subroutine warm_start

  !> Solve all contacts of `set` for the velocities `v` (3, n_bodies), which enter as the
  !> free velocities plus the effect of the impulses already in `set` and leave as the
  !> end-of-step velocities. Convergence: the 'Quad' norm
  !> sqrt(sum dr.W.dr / sum r.W.r) of one sweep's change of impulses below `tol`.
  subroutine nlgs_solve(bodies, set, work, v, tol, max_iter, iterations, norm, converged)
    type(bodies_t), intent(in) :: bodies
    type(contact_set_t), intent(inout) :: set
    type(nlgs_work_t), intent(inout) :: work
    real(dp), intent(inout) :: v(:, :)
    real(dp), intent(in) :: tol
    integer, intent(in) :: max_iter
    integer, intent(out) :: iterations
    real(dp), intent(out) :: norm
    logical, intent(out) :: converged
    integer :: it, k, a, b
    real(dp) :: u_t, u_n, r_old(2), r_new(2), dr(2), sum_change, sum_energy
    real(dp) :: ima, imb, iia, iib

    iterations = 0
    norm = 0.0_dp
    converged = .true.
    if (set%n == 0) return
    converged = .false.
    do it = 1, max_iter
      sum_change = 0.0_dp
      sum_energy = 0.0_dp
      do k = 1, set%n
        a = set%body_a(k)
        b = set%body_b(k)
        associate (t => set%tangent(:, k), n => set%normal(:, k))
          u_t = t(1)*(v(1, a) - v(1, b)) + t(2)*(v(2, a) - v(2, b)) &
                + work%arm_at(k)*v(3, a) - work%arm_bt(k)*v(3, b)
          u_n = n(1)*(v(1, a) - v(1, b)) + n(2)*(v(2, a) - v(2, b)) &
                + work%arm_an(k)*v(3, a) - work%arm_bn(k)*v(3, b)
          r_old = set%impulse(:, k)
          ! Free local velocity: remove this contact's own contribution.
          u_t = u_t - work%w_tt(k)*r_old(1) - work%w_tn(k)*r_old(2)
          u_n = u_n - work%w_tn(k)*r_old(1) - work%w_nn(k)*r_old(2) + work%shift(k)
          call coulomb_local(work%w_tt(k), work%w_tn(k), work%w_nn(k), work%det(k), &
                             u_t, u_n, set%friction(k), r_new)
          dr = r_new - r_old
          set%impulse(:, k) = r_new
          ima = bodies%inv_mass(a)
          iia = bodies%inv_inertia(a)
          imb = bodies%inv_mass(b)
          iib = bodies%inv_inertia(b)
          v(1, a) = v(1, a) + ima*(dr(1)*t(1) + dr(2)*n(1))
          v(2, a) = v(2, a) + ima*(dr(1)*t(2) + dr(2)*n(2))
          v(3, a) = v(3, a) + iia*(dr(1)*work%arm_at(k) + dr(2)*work%arm_an(k))
          v(1, b) = v(1, b) - imb*(dr(1)*t(1) + dr(2)*n(1))
          v(2, b) = v(2, b) - imb*(dr(1)*t(2) + dr(2)*n(2))
          v(3, b) = v(3, b) - iib*(dr(1)*work%arm_bt(k) + dr(2)*work%arm_bn(k))
        end associate
        sum_change = sum_change + work%w_tt(k)*dr(1)**2 + 2.0_dp*work%w_tn(k)*dr(1)*dr(2) &
                     + work%w_nn(k)*dr(2)**2
        sum_energy = sum_energy + work%w_tt(k)*r_new(1)**2 + 2.0_dp*work%w_tn(k)*r_new(1)*r_new(2) &
                     + work%w_nn(k)*r_new(2)**2
      end do
      iterations = it
      if (sum_energy > 0.0_dp) then
        norm = sqrt(sum_change/sum_energy)
      else
        norm = sqrt(sum_change)
      end if
      if (.not. (norm == norm)) return   ! NaN: the caller reports it
      if (norm < tol) then
        converged = .true.
        return
      end if
    end do
  end subroutine nlgs_solve

  !> Exact solution of the local inelastic Signorini-Coulomb problem
  !>   u = u_free + W r,  0 <= u_n  _|_  r_n >= 0,  |r_t| <= mu r_n, r_t opposes u_t,
  !> with W = [[w_tt, w_tn], [w_tn, w_nn]] and (u_t_free, u_n_free) shifted by the gap.
  !> Returns r = (r_t, r_n). Cases in turn: no contact, stick, slide in either direction.
  pure subroutine coulomb_local(w_tt, w_tn, w_nn, det, u_t_free, u_n_free, mu, r)
    real(dp), intent(in) :: w_tt, w_tn, w_nn, det, u_t_free, u_n_free, mu
    real(dp), intent(out) :: r(2)
    real(dp) :: r_t, r_n, sigma, denom, u_t
    integer :: attempt

    r = 0.0_dp
    if (u_n_free >= 0.0_dp) return
    ! Stick: u = 0.
    r_t = -(w_nn*u_t_free - w_tn*u_n_free)/det
    r_n = -(w_tt*u_n_free - w_tn*u_t_free)/det
    if (r_n >= 0.0_dp .and. abs(r_t) <= mu*r_n) then
      r = [r_t, r_n]
      return
    end if
    ! Slide with u_t of sign sigma and r_t = -sigma mu r_n; try the direction the
    ! stick trial points to first.
    sigma = -sign(1.0_dp, r_t)
    do attempt = 1, 2
      denom = w_nn - sigma*mu*w_tn
      if (denom > 0.0_dp) then
        r_n = -u_n_free/denom
        u_t = u_t_free + r_n*(w_tn - sigma*mu*w_tt)
        if (r_n >= 0.0_dp .and. sigma*u_t >= 0.0_dp) then
          r = [-sigma*mu*r_n, r_n]
          return
        end if
      end if
      sigma = -sigma
    end do
    ! Degenerate W (should not happen for a positive definite block): frictionless push.
    r = [0.0_dp, max(0.0_dp, -u_n_free/w_nn)]
  end subroutine coulomb_local

end module voussoir_nlgs
