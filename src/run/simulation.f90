!> A whole run: the time loop, its monitors (crown, collapse, hinges) and the record.
module voussoir_simulation
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t
  use voussoir_assembly, only: assembly_t, role_voussoir
  use voussoir_model, only: model_t, model_step
  use voussoir_hinge_side, only: side_intrados, side_extrados
  use voussoir_interrupt, only: stop_signal
  implicit none
  private

  public :: monitor_t, run_result_t, monitor_init, simulate

  integer, parameter :: joint_closed = -1

  !> What the run watches: crown, collapse, hinges at the joints of an arch.
  type :: monitor_t
    real(dp) :: collapse_drop_m = 0.0_dp
    real(dp) :: collapse_rotation_rad = 0.5_dp
    real(dp) :: hinge_gap_m = 0.0_dp
    integer, allocatable :: crown_bodies(:)
    integer :: table_body = 0
    integer :: n_joints = 0                  !! n + 1 for an arch, 0 otherwise
    integer, allocatable :: joint_bodies(:, :)  !! (2, n_joints): left, right body
    real(dp), allocatable :: joint_ends(:, :, :) !! (2, 2, n_joints): intrados, extrados point
    real(dp), allocatable :: joint_normal(:, :)  !! (2, n_joints): from right body to left
    integer, allocatable :: joint_state(:)
  end type monitor_t

  !> The record of a run.
  type :: run_result_t
    integer :: n_samples = 0
    real(dp), allocatable :: time_s(:), table(:, :), crown(:, :), q(:, :, :)
    integer, allocatable :: contact_count(:)
    integer :: n_steps = 0
    real(dp), allocatable :: step_time_s(:), step_norm(:)
    integer, allocatable :: step_iterations(:)
    integer :: n_hinges = 0
    real(dp), allocatable :: hinge_time_s(:)
    integer, allocatable :: hinge_joint(:), hinge_side(:)
    logical :: collapsed = .false.
    real(dp) :: collapse_time_s = 0.0_dp
    integer :: interrupted_by = 0        !! the signal that stopped the run early (0: it ran to its end)
    real(dp) :: peak_crown_disp_m = 0.0_dp
    !> Where the free blocks ended up: the largest displacement of one of them relative to
    !> the table at the end of the run [m], and which (a wall that slid has not just "stood").
    real(dp) :: max_residual_disp_m = 0.0_dp
    integer :: max_residual_body = 0
    real(dp) :: mean_iterations = 0.0_dp
    integer :: max_iterations = 0
    integer :: nonconverged_steps = 0
    real(dp) :: wall_time_s = 0.0_dp
  end type run_result_t

contains

  !> Monitors for `assembly` as built: the crown is the keystone of an arch (the two
  !> central voussoirs for an even number) or else the highest free body.
  subroutine monitor_init(assembly, model, collapse_drop_m, collapse_rotation_rad, hinge_gap_m, mon)
    type(assembly_t), intent(in) :: assembly
    type(model_t), intent(in) :: model
    real(dp), intent(in) :: collapse_drop_m, collapse_rotation_rad, hinge_gap_m
    type(monitor_t), intent(out) :: mon
    integer :: n, j, k
    real(dp) :: d(2), nrm(2)

    mon%collapse_drop_m = collapse_drop_m
    mon%collapse_rotation_rad = collapse_rotation_rad
    mon%hinge_gap_m = hinge_gap_m
    n = assembly%n_voussoirs
    mon%table_body = 0
    do k = 1, assembly%n_bodies
      if (assembly%driven(k)) then
        mon%table_body = k
        exit
      end if
    end do
    if (n > 0) then
      if (modulo(n, 2) == 1) then
        mon%crown_bodies = [(n + 1)/2]
      else
        mon%crown_bodies = [n/2, n/2 + 1]
      end if
      mon%n_joints = n + 1
      allocate (mon%joint_bodies(2, n + 1), mon%joint_ends(2, 2, n + 1), mon%joint_normal(2, n + 1), &
                mon%joint_state(n + 1))
      do j = 0, n
        mon%joint_bodies(:, j + 1) = assembly%joint_bodies(:, j)
        mon%joint_ends(:, 1, j + 1) = assembly%joint_intrados_xy(:, j)
        mon%joint_ends(:, 2, j + 1) = assembly%joint_extrados_xy(:, j)
        d = assembly%joint_extrados_xy(:, j) - assembly%joint_intrados_xy(:, j)
        nrm = [-d(2), d(1)]/norm2(d)
        ! Orient from the right body towards the left one.
        k = assembly%joint_bodies(1, j)
        if (dot_product(nrm, model%bodies%q_ref(1:2, k) - assembly%joint_intrados_xy(:, j)) < 0.0_dp) &
          nrm = -nrm
        mon%joint_normal(:, j + 1) = nrm
      end do
      mon%joint_state = joint_closed
    else
      k = maxloc(model%bodies%q_ref(2, :), dim=1, mask=.not. model%bodies%driven)
      mon%crown_bodies = [k]
    end if
  end subroutine monitor_init

  !> Run `model` for `duration_s`, sampling every `every` steps; stop
  !> `stop_after_collapse_s` after a collapse (never when negative).
  subroutine simulate(model, mon, duration_s, every, stop_after_collapse_s, res, status)
    type(model_t), intent(inout) :: model
    type(monitor_t), intent(inout) :: mon
    real(dp), intent(in) :: duration_s, stop_after_collapse_s
    integer, intent(in) :: every
    type(run_result_t), intent(out) :: res
    type(status_t), intent(inout) :: status
    integer :: n_steps, n_samples, nb, istep
    integer(8) :: clock0, clock1, rate
    real(dp) :: sum_iter
    real(dp) :: cs(2, model%bodies%n)  ! cos and sin of every body's rotation

    call system_clock(clock0, rate)
    nb = model%bodies%n
    n_steps = max(1, nint(duration_s/model%solver%dt_s))
    n_samples = n_steps/every + 2  ! t = 0, every multiple of `every`, and the last step
    allocate (res%time_s(n_samples), res%table(3, n_samples), res%crown(2, n_samples), &
              res%q(3, nb, n_samples), res%contact_count(n_samples), res%step_time_s(n_steps), &
              res%step_norm(n_steps), res%step_iterations(n_steps), res%hinge_time_s(16), &
              res%hinge_joint(16), res%hinge_side(16))
    res%collapse_time_s = ieee_value(1.0_dp, ieee_quiet_nan)
    call sample()
    sum_iter = 0.0_dp
    do istep = 1, n_steps
      call model_step(model, status)
      if (.not. status%ok) exit
      res%n_steps = istep
      res%step_time_s(istep) = model%t_s
      res%step_iterations(istep) = model%iterations
      res%step_norm(istep) = model%norm
      sum_iter = sum_iter + model%iterations
      call watch()
      if (modulo(istep, every) == 0) call sample()
      if (res%collapsed .and. stop_after_collapse_s >= 0.0_dp) then
        if (model%t_s >= res%collapse_time_s + stop_after_collapse_s) exit
      end if
      res%interrupted_by = stop_signal()
      if (res%interrupted_by /= 0) exit
    end do
    if (res%n_steps > 0) then
      if (modulo(res%n_steps, every) /= 0) call sample()
      res%mean_iterations = sum_iter/res%n_steps
      res%max_iterations = maxval(res%step_iterations(1:res%n_steps))
    end if
    res%nonconverged_steps = model%nonconverged_steps
    call residual_displacement()
    res%time_s = res%time_s(1:res%n_samples)
    res%table = res%table(:, 1:res%n_samples)
    res%crown = res%crown(:, 1:res%n_samples)
    res%q = res%q(:, :, 1:res%n_samples)
    res%contact_count = res%contact_count(1:res%n_samples)
    res%step_time_s = res%step_time_s(1:res%n_steps)
    res%step_norm = res%step_norm(1:res%n_steps)
    res%step_iterations = res%step_iterations(1:res%n_steps)
    res%hinge_time_s = res%hinge_time_s(1:res%n_hinges)
    res%hinge_joint = res%hinge_joint(1:res%n_hinges)
    res%hinge_side = res%hinge_side(1:res%n_hinges)
    call system_clock(clock1)
    res%wall_time_s = real(clock1 - clock0, dp)/real(rate, dp)

  contains

    subroutine sample()
      integer :: s
      res%n_samples = res%n_samples + 1
      s = res%n_samples
      res%time_s(s) = model%t_s
      res%table(:, s) = model%table
      res%crown(:, s) = crown_displacement()
      res%q(:, :, s) = model%bodies%q
      res%contact_count(s) = 0
      if (model%contacts%n > 0) &
        res%contact_count(s) = count(model%contacts%impulse(2, 1:model%contacts%n) > 0.0_dp)
    end subroutine sample

    function crown_displacement() result(d)
      real(dp) :: d(2)
      integer :: k
      d = 0.0_dp
      do k = 1, size(mon%crown_bodies)
        d = d + model%bodies%q(1:2, mon%crown_bodies(k)) - model%bodies%q_ref(1:2, mon%crown_bodies(k))
      end do
      d = d/size(mon%crown_bodies)
      if (mon%table_body > 0) d(1) = d(1) - (model%bodies%q(1, mon%table_body) &
                                             - model%bodies%q_ref(1, mon%table_body))
    end function crown_displacement

    subroutine residual_displacement()
      integer :: i
      real(dp) :: table(2), d
      table = 0.0_dp
      if (mon%table_body > 0) table = model%bodies%q(1:2, mon%table_body) - model%bodies%q_ref(1:2, mon%table_body)
      do i = 1, nb
        if (model%bodies%driven(i)) cycle
        d = norm2(model%bodies%q(1:2, i) - model%bodies%q_ref(1:2, i) - table)
        if (d > res%max_residual_disp_m) then
          res%max_residual_disp_m = d
          res%max_residual_body = i
        end if
      end do
    end subroutine residual_displacement

    subroutine watch()
      integer :: i, j, side
      real(dp) :: gaps(2)
      if (mon%n_joints > 0) then
        ! Rotation of every body, once per step (the joints share them).
        cs(1, :) = cos(model%bodies%q(3, :))
        cs(2, :) = sin(model%bodies%q(3, :))
      end if
      res%peak_crown_disp_m = max(res%peak_crown_disp_m, norm2(crown_displacement()))
      if (.not. res%collapsed) then
        do i = 1, nb
          if (model%bodies%role(i) /= role_voussoir) cycle
          if (model%bodies%q_ref(2, i) - model%bodies%q(2, i) > mon%collapse_drop_m .or. &
              abs(model%bodies%q(3, i)) > mon%collapse_rotation_rad) then
            res%collapsed = .true.
            res%collapse_time_s = model%t_s
            exit
          end if
        end do
      end if
      do j = 1, mon%n_joints
        gaps = joint_gaps(j)
        ! A hinge pivots on the edge that stays shut while the other opens; it closes
        ! again (hysteresis) when both ends are back within half the opening gap.
        side = mon%joint_state(j)
        if (gaps(2) > mon%hinge_gap_m .and. gaps(1) < 0.5_dp*mon%hinge_gap_m) then
          side = side_intrados
        else if (gaps(1) > mon%hinge_gap_m .and. gaps(2) < 0.5_dp*mon%hinge_gap_m) then
          side = side_extrados
        else if (maxval(gaps) < 0.5_dp*mon%hinge_gap_m) then
          side = joint_closed
        end if
        if (side /= mon%joint_state(j) .and. side /= joint_closed) call add_hinge(j - 1, side)
        mon%joint_state(j) = side
      end do
    end subroutine watch

    !> Opening of joint j at its intrados and extrados ends: distance of the left body's
    !> end points from the right body's face, positive when apart.
    function joint_gaps(j) result(gaps)
      integer, intent(in) :: j
      real(dp) :: gaps(2), pa(2), pb(2), nrm(2)
      integer :: a, b, e
      a = mon%joint_bodies(1, j)
      b = mon%joint_bodies(2, j)
      nrm = rotated(mon%joint_normal(:, j), b)
      pb = material_point(b, mon%joint_ends(:, 1, j))
      do e = 1, 2
        pa = material_point(a, mon%joint_ends(:, e, j))
        gaps(e) = dot_product(pa - pb, nrm)
      end do
    end function joint_gaps

    function material_point(body, x_ref) result(x)
      integer, intent(in) :: body
      real(dp), intent(in) :: x_ref(2)
      real(dp) :: x(2)
      x = model%bodies%q(1:2, body) + rotated(x_ref - model%bodies%q_ref(1:2, body), body)
    end function material_point

    !> `p` turned by the present rotation of `body`.
    function rotated(p, body) result(r)
      real(dp), intent(in) :: p(2)
      integer, intent(in) :: body
      real(dp) :: r(2)
      r = [cs(1, body)*p(1) - cs(2, body)*p(2), cs(2, body)*p(1) + cs(1, body)*p(2)]
    end function rotated

    subroutine add_hinge(joint, side)
      integer, intent(in) :: joint, side
      if (res%n_hinges == size(res%hinge_time_s)) then
        res%hinge_time_s = [res%hinge_time_s, res%hinge_time_s]
        res%hinge_joint = [res%hinge_joint, res%hinge_joint]
        res%hinge_side = [res%hinge_side, res%hinge_side]
      end if
      res%n_hinges = res%n_hinges + 1
      res%hinge_time_s(res%n_hinges) = model%t_s
      res%hinge_joint(res%n_hinges) = joint
      res%hinge_side(res%n_hinges) = side
    end subroutine add_hinge

  end subroutine simulate

end module voussoir_simulation
