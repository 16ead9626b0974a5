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
  use voussoir_contact_rows, only: i_t, i_n, i_arm_at, i_arm_an, i_arm_bt, i_arm_bn, i_w_tt, i_w_tn, &
                                   i_w_nn, i_det, i_shift, i_mu, i_ima, i_iia, i_imb, i_iib, n_rows
  use voussoir_coarse, only: coarse_t, coarse_correct, coarse_period, coarse_last_sweep
  implicit none
  private

  public :: nlgs_work_t, nlgs_prepare, nlgs_solve, coulomb_local, warm_start

  !> Per-contact data of the solve, packed contact by contact for the hot loop.
  type :: nlgs_work_t
    real(dp), allocatable :: data(:, :)   !! (n_rows, capacity)
    integer, allocatable :: pair(:, :)    !! (2, capacity) bodies a and b
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
    integer :: k, a, b
    real(dp) :: at, an, bt, bn, ima, iia, imb, iib, w_tt, w_tn, w_nn

    if (allocated(work%data)) then
      if (size(work%data, 2) < set%n) deallocate (work%data, work%pair)
    end if
    if (.not. allocated(work%data)) allocate (work%data(n_rows, max(64, 2*set%n)), &
                                              work%pair(2, max(64, 2*set%n)))
    do k = 1, set%n
      a = set%body_a(k)
      b = set%body_b(k)
      associate (t => set%tangent(:, k), n => set%normal(:, k), ra => set%arm_a(:, k), &
                 rb => set%arm_b(:, k), c => work%data(:, k))
        at = ra(1)*t(2) - ra(2)*t(1)
        an = ra(1)*n(2) - ra(2)*n(1)
        bt = rb(1)*t(2) - rb(2)*t(1)
        bn = rb(1)*n(2) - rb(2)*n(1)
        ima = bodies%inv_mass(a)
        iia = bodies%inv_inertia(a)
        imb = bodies%inv_mass(b)
        iib = bodies%inv_inertia(b)
        w_tt = ima + iia*at**2 + imb + iib*bt**2
        w_nn = ima + iia*an**2 + imb + iib*bn**2
        w_tn = iia*at*an + iib*bt*bn
        work%pair(1, k) = a
        work%pair(2, k) = b
        c(i_t) = t(1)
        c(i_t + 1) = t(2)
        c(i_n) = n(1)
        c(i_n + 1) = n(2)
        c(i_arm_at) = at
        c(i_arm_an) = an
        c(i_arm_bt) = bt
        c(i_arm_bn) = bn
        c(i_w_tt) = w_tt
        c(i_w_tn) = w_tn
        c(i_w_nn) = w_nn
        c(i_det) = w_tt*w_nn - w_tn**2
        c(i_shift) = max(0.0_dp, set%gap_m(k))/h_theta_s
        c(i_mu) = set%friction(k)
        c(i_ima) = ima
        c(i_iia) = iia
        c(i_imb) = imb
        c(i_iib) = iib
      end associate
    end do
  end subroutine nlgs_prepare

  !> First guess of the impulses: for a contact that existed at the previous step (same
  !> bodies, same slot), its impulse then. (A linear extrapolation from the last two
  !> steps was tried and made the solve slower: the impulses of a hyperstatic arch are
  !> not unique and wander between equivalent distributions from step to step.)
  !> `remember` stores the present set for the next step.
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
            set%impulse(1, k) = work%prev_impulse(1, m)
            set%impulse(2, k) = work%prev_impulse(2, m)
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
      work%prev_impulse(1, pos) = set%impulse(1, k)
      work%prev_impulse(2, pos) = set%impulse(2, k)
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
  !> With `coarse` (a wall's courses), a coarse correction of the impulses per bed joint
  !> after the first sweep and every `coarse_period` sweeps after it, up to sweep
  !> `coarse_last_sweep` (voussoir_coarse); the test of convergence is always that of a
  !> sweep.
  subroutine nlgs_solve(set, work, v, tol, max_iter, iterations, norm, converged, coarse)
    type(contact_set_t), intent(inout) :: set
    type(nlgs_work_t), intent(in) :: work
    real(dp), intent(inout) :: v(:, :)
    real(dp), intent(in) :: tol
    integer, intent(in) :: max_iter
    integer, intent(out) :: iterations
    real(dp), intent(out) :: norm
    logical, intent(out) :: converged
    type(coarse_t), intent(inout), optional :: coarse
    integer :: it
    real(dp) :: sum_change, sum_energy
    logical :: with_coarse

    iterations = 0
    norm = 0.0_dp
    converged = .true.
    if (set%n == 0) return
    converged = .false.
    with_coarse = .false.
    if (present(coarse)) with_coarse = coarse%n_joints > 0
    do it = 1, max_iter
      call gauss_seidel_sweep(set%n, size(v, 2), work%pair, work%data, set%impulse, v, &
                              sum_change, sum_energy)
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
      if (with_coarse) then
        if (mod(it - 1, coarse_period) == 0 .and. it <= coarse_last_sweep) &
          call coarse_correct(coarse, set%n, size(v, 2), work%pair, work%data, set%point, set%impulse, v)
      end if
    end do
  end subroutine nlgs_solve

  !> One sweep over the contacts in order: local solve, then update of the two bodies.
  !> Returns the sums of dr.W.dr and r.W.r for the convergence norm.
  pure subroutine gauss_seidel_sweep(n, n_bodies, pair, c, r, v, sum_change, sum_energy)
    integer, intent(in) :: n, n_bodies
    integer, intent(in) :: pair(2, n)
    real(dp), intent(in) :: c(n_rows, n)
    real(dp), intent(inout) :: r(2, n), v(3, n_bodies)
    real(dp), intent(out) :: sum_change, sum_energy
    integer :: k, a, b, a_held, b_held
    real(dp) :: u_t, u_n, r_t, r_n, dr_t, dr_n, dvx, dvy, px, py, w_tt, w_tn, w_nn, va(3), vb(3), va_next(3)

    sum_change = 0.0_dp
    sum_energy = 0.0_dp
    a_held = 0
    b_held = 0
    do k = 1, n
      a = pair(1, k)
      b = pair(2, k)
      ! Consecutive contacts share bodies (the two points of a face, the pairs of one
      ! body): keep the last contact's velocities at hand (v is always up to date).
      if (a == a_held) then
        va_next = va
      else if (a == b_held) then
        va_next = vb
      else
        va_next = v(:, a)
      end if
      if (b == a_held) then
        vb = va
      else if (b /= b_held) then
        vb = v(:, b)
      end if
      va = va_next
      a_held = a
      b_held = b
      w_tt = c(i_w_tt, k)
      w_tn = c(i_w_tn, k)
      w_nn = c(i_w_nn, k)
      dvx = va(1) - vb(1)
      dvy = va(2) - vb(2)
      ! Free local velocity: the present one less this contact's own contribution.
      u_t = c(1, k)*dvx + c(2, k)*dvy + c(i_arm_at, k)*va(3) - c(i_arm_bt, k)*vb(3) &
            - w_tt*r(1, k) - w_tn*r(2, k)
      u_n = c(3, k)*dvx + c(4, k)*dvy + c(i_arm_an, k)*va(3) - c(i_arm_bn, k)*vb(3) &
            - w_tn*r(1, k) - w_nn*r(2, k) + c(i_shift, k)
      ! The two common cases inline (open, stick); the local solve handles the rest.
      if (u_n >= 0.0_dp) then
        r_t = 0.0_dp
        r_n = 0.0_dp
      else
        r_t = -(w_nn*u_t - w_tn*u_n)/c(i_det, k)
        r_n = -(w_tt*u_n - w_tn*u_t)/c(i_det, k)
        if (.not. (r_n >= 0.0_dp .and. abs(r_t) <= c(i_mu, k)*r_n)) &
          call coulomb_slide(w_tt, w_tn, w_nn, u_t, u_n, c(i_mu, k), r_t, r_n)
      end if
      dr_t = r_t - r(1, k)
      dr_n = r_n - r(2, k)
      r(1, k) = r_t
      r(2, k) = r_n
      px = dr_t*c(1, k) + dr_n*c(3, k)
      py = dr_t*c(2, k) + dr_n*c(4, k)
      va(1) = va(1) + c(i_ima, k)*px
      va(2) = va(2) + c(i_ima, k)*py
      va(3) = va(3) + c(i_iia, k)*(dr_t*c(i_arm_at, k) + dr_n*c(i_arm_an, k))
      vb(1) = vb(1) - c(i_imb, k)*px
      vb(2) = vb(2) - c(i_imb, k)*py
      vb(3) = vb(3) - c(i_iib, k)*(dr_t*c(i_arm_bt, k) + dr_n*c(i_arm_bn, k))
      v(:, a) = va
      v(:, b) = vb
      sum_change = sum_change + w_tt*dr_t*dr_t + 2.0_dp*w_tn*dr_t*dr_n + w_nn*dr_n*dr_n
      sum_energy = sum_energy + w_tt*r_t*r_t + 2.0_dp*w_tn*r_t*r_n + w_nn*r_n*r_n
    end do
  end subroutine gauss_seidel_sweep


  !> Exact solution of the local inelastic Signorini-Coulomb problem
  !>   u = u_free + W r,  0 <= u_n  _|_  r_n >= 0,  |r_t| <= mu r_n, r_t opposes u_t,
  !> with W = [[w_tt, w_tn], [w_tn, w_nn]] and (u_t_free, u_n_free) shifted by the gap.
  !> Returns r = (r_t, r_n). Cases in turn: no contact, stick, slide in either direction.
  pure subroutine coulomb_local(w_tt, w_tn, w_nn, det, u_t_free, u_n_free, mu, r)
    real(dp), intent(in) :: w_tt, w_tn, w_nn, det, u_t_free, u_n_free, mu
    real(dp), intent(out) :: r(2)
    real(dp) :: r_t, r_n

    r = 0.0_dp
    if (u_n_free >= 0.0_dp) return
    ! Stick: u = 0.
    r_t = -(w_nn*u_t_free - w_tn*u_n_free)/det
    r_n = -(w_tt*u_n_free - w_tn*u_t_free)/det
    if (.not. (r_n >= 0.0_dp .and. abs(r_t) <= mu*r_n)) &
      call coulomb_slide(w_tt, w_tn, w_nn, u_t_free, u_n_free, mu, r_t, r_n)
    r = [r_t, r_n]
  end subroutine coulomb_local

  !> The sliding (or, for a degenerate W, frictionless) solution of the local problem of
  !> `coulomb_local` once the stick trial (r_t, r_n) has left the cone: on entry that
  !> trial, on return the solution. Slide with u_t of sign sigma and r_t = -sigma mu r_n;
  !> the direction the stick trial points to is tried first. (Private, so that the
  !> compiler inlines it into the sweep, which then keeps its values in registers.)
  pure subroutine coulomb_slide(w_tt, w_tn, w_nn, u_t_free, u_n_free, mu, r_t, r_n)
    real(dp), value :: w_tt, w_tn, w_nn, u_t_free, u_n_free, mu
    real(dp), intent(inout) :: r_t, r_n
    real(dp) :: sigma, denom, u_t
    integer :: attempt

    sigma = -sign(1.0_dp, r_t)
    do attempt = 1, 2
      denom = w_nn - sigma*mu*w_tn
      if (denom > 0.0_dp) then
        r_n = -u_n_free/denom
        u_t = u_t_free + r_n*(w_tn - sigma*mu*w_tt)
        if (r_n >= 0.0_dp .and. sigma*u_t >= 0.0_dp) then
          r_t = -sigma*mu*r_n
          return
        end if
      end if
      sigma = -sigma
    end do
    ! Degenerate W (should not happen for a positive definite block): frictionless push.
    r_t = 0.0_dp
    r_n = max(0.0_dp, -u_n_free/w_nn)
  end subroutine coulomb_slide

end module voussoir_nlgs
