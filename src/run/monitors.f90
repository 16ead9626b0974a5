!> The run monitors: the crown's displacement, the collapse, the hinges at the joints of
!> an arch, and where the free blocks ended up.
!>
!> Set up from an assembly (`monitor_init`), then updated once per step from the bodies'
!> positions alone (`monitor_update`): what they have seen stays in the monitor, so a test
!> can drive them with positions made by hand, without a time loop.
module voussoir_monitors
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use voussoir_kinds, only: dp
  use voussoir_assembly, only: assembly_t, role_voussoir, role_fill, role_backing
  use voussoir_bodies, only: bodies_t
  use voussoir_hinge_side, only: side_intrados, side_extrados
  implicit none
  private

  public :: monitor_t, monitor_init, monitor_clear, monitor_update, crown_displacement, residual_displacement
  public :: joint_closed, joint_of_pair

  integer, parameter :: joint_closed = -1   !! a joint's state when no hinge is open in it

  !> What the run watches (crown, collapse, hinges at the joints of an arch) and what it
  !> has seen since `monitor_clear`.
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
    integer, allocatable :: joint_state(:)       !! (n_joints) `joint_closed` or the side of its open hinge
    integer, allocatable :: body_joints(:, :)    !! (2, n_bodies): the joints (1..n_joints) of each body, 0: none
    ! Seen so far:
    logical :: collapsed = .false.
    real(dp) :: collapse_time_s = 0.0_dp     !! NaN until a collapse
    real(dp) :: peak_crown_disp_m = 0.0_dp
    !> The largest opening of an arch joint at either end [m] (0 when not an arch)
    real(dp) :: peak_joint_opening_m = 0.0_dp
    integer :: n_hinges = 0                  !! hinges opened, in order (hinge_* (1:n_hinges))
    real(dp), allocatable :: hinge_time_s(:)
    integer, allocatable :: hinge_joint(:)   !! joint 0..n
    integer, allocatable :: hinge_side(:)    !! `side_intrados` or `side_extrados`
  end type monitor_t

contains

  !> Monitors for `assembly` as built, its bodies at rest in `bodies`: the crown is the
  !> keystone of an arch (the two central voussoirs for an even number) or else the
  !> highest free body. Every joint starts closed, nothing seen.
  subroutine monitor_init(assembly, bodies, collapse_drop_m, collapse_rotation_rad, hinge_gap_m, mon)
    type(assembly_t), intent(in) :: assembly
    type(bodies_t), intent(in) :: bodies
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
        if (dot_product(nrm, bodies%q_ref(1:2, k) - assembly%joint_intrados_xy(:, j)) < 0.0_dp) &
          nrm = -nrm
        mon%joint_normal(:, j + 1) = nrm
      end do
      mon%joint_state = joint_closed
      allocate (mon%body_joints(2, assembly%n_bodies))
      mon%body_joints = 0
      do j = 1, n + 1
        do k = 1, 2
          associate (slot => mon%body_joints(:, mon%joint_bodies(k, j)))
            if (slot(1) == 0) then
              slot(1) = j
            else
              slot(2) = j
            end if
          end associate
        end do
      end do
    else
      ! The highest free block of the structure (a fill's particles and the backing are not the crown).
      k = maxloc(bodies%q_ref(2, :), dim=1, mask=.not. bodies%driven .and. bodies%role /= role_fill .and. &
                   bodies%role /= role_backing)
      mon%crown_bodies = [k]
    end if
    call monitor_clear(mon)
  end subroutine monitor_init

  !> Forget what the monitors have seen (collapse, peak, hinges); the joints keep their state.
  subroutine monitor_clear(mon)
    type(monitor_t), intent(inout) :: mon
    mon%collapsed = .false.
    mon%collapse_time_s = ieee_value(1.0_dp, ieee_quiet_nan)
    mon%peak_crown_disp_m = 0.0_dp
    mon%peak_joint_opening_m = 0.0_dp
    mon%n_hinges = 0
    if (allocated(mon%hinge_time_s)) deallocate (mon%hinge_time_s, mon%hinge_joint, mon%hinge_side)
    allocate (mon%hinge_time_s(16), mon%hinge_joint(16), mon%hinge_side(16))
  end subroutine monitor_clear

  !> Watch the bodies at time `t_s`: the peak crown displacement, the first collapse (a
  !> voussoir dropped by more than `collapse_drop_m` or turned by more than
  !> `collapse_rotation_rad`), every hinge that opens and the largest joint opening.
  !>
  !> A hinge pivots on the edge that stays shut while the other opens by more than
  !> `hinge_gap_m`; the joint closes again (hysteresis) when both ends are back within
  !> half that gap, and only then can the same hinge open again.
  subroutine monitor_update(mon, bodies, t_s)
    type(monitor_t), intent(inout) :: mon
    type(bodies_t), intent(in) :: bodies
    real(dp), intent(in) :: t_s
    real(dp) :: cs(2, bodies%n)  ! cos and sin of every body's rotation
    integer :: i, j, side
    real(dp) :: gaps(2), table_dy

    if (mon%n_joints > 0) then
      ! Rotation of every body, once per step (the joints share them).
      cs(1, :) = cos(bodies%q(3, :))
      cs(2, :) = sin(bodies%q(3, :))
    end if
    mon%peak_crown_disp_m = max(mon%peak_crown_disp_m, norm2(crown_displacement(mon, bodies)))
    if (.not. mon%collapsed) then
      ! A drop is measured from the table, which may move vertically.
      table_dy = 0.0_dp
      if (mon%table_body > 0) table_dy = bodies%q(2, mon%table_body) - bodies%q_ref(2, mon%table_body)
      do i = 1, bodies%n
        if (bodies%role(i) /= role_voussoir) cycle
        if (bodies%q_ref(2, i) - (bodies%q(2, i) - table_dy) > mon%collapse_drop_m .or. &
            abs(bodies%q(3, i)) > mon%collapse_rotation_rad) then
          mon%collapsed = .true.
          mon%collapse_time_s = t_s
          exit
        end if
      end do
    end if
    do j = 1, mon%n_joints
      gaps = joint_gaps(mon, bodies, cs, j)
      mon%peak_joint_opening_m = max(mon%peak_joint_opening_m, maxval(gaps))
      side = mon%joint_state(j)
      if (gaps(2) > mon%hinge_gap_m .and. gaps(1) < 0.5_dp*mon%hinge_gap_m) then
        side = side_intrados
      else if (gaps(1) > mon%hinge_gap_m .and. gaps(2) < 0.5_dp*mon%hinge_gap_m) then
        side = side_extrados
      else if (maxval(gaps) < 0.5_dp*mon%hinge_gap_m) then
        side = joint_closed
      end if
      if (side /= mon%joint_state(j) .and. side /= joint_closed) call add_hinge(mon, j - 1, side, t_s)
      mon%joint_state(j) = side
    end do
  end subroutine monitor_update

  !> The joint (0..n) of an arch between bodies `a` and `b`, -1 when they share none (a
  !> bracket, or an assembly that is not an arch).
  pure integer function joint_of_pair(mon, a, b)
    type(monitor_t), intent(in) :: mon
    integer, intent(in) :: a, b
    integer :: k, j
    joint_of_pair = -1
    if (mon%n_joints == 0) return
    do k = 1, 2
      j = mon%body_joints(k, a)
      if (j == 0) cycle
      if (any(mon%joint_bodies(:, j) == b)) then
        joint_of_pair = j - 1
        return
      end if
    end do
  end function joint_of_pair

  !> Mean displacement of the crown bodies from their reference [m], relative to the table.
  pure function crown_displacement(mon, bodies) result(d)
    type(monitor_t), intent(in) :: mon
    type(bodies_t), intent(in) :: bodies
    real(dp) :: d(2)
    integer :: k
    d = 0.0_dp
    do k = 1, size(mon%crown_bodies)
      d = d + bodies%q(1:2, mon%crown_bodies(k)) - bodies%q_ref(1:2, mon%crown_bodies(k))
    end do
    d = d/size(mon%crown_bodies)
    if (mon%table_body > 0) d = d - (bodies%q(1:2, mon%table_body) - bodies%q_ref(1:2, mon%table_body))
  end function crown_displacement

  !> The largest displacement of a free body relative to the table [m] and which body
  !> (0 and 0 when none has moved).
  pure subroutine residual_displacement(mon, bodies, disp_m, body)
    type(monitor_t), intent(in) :: mon
    type(bodies_t), intent(in) :: bodies
    real(dp), intent(out) :: disp_m
    integer, intent(out) :: body
    integer :: i
    real(dp) :: table(2), d
    disp_m = 0.0_dp
    body = 0
    table = 0.0_dp
    if (mon%table_body > 0) table = bodies%q(1:2, mon%table_body) - bodies%q_ref(1:2, mon%table_body)
    do i = 1, bodies%n
      if (bodies%driven(i)) cycle
      d = norm2(bodies%q(1:2, i) - bodies%q_ref(1:2, i) - table)
      if (d > disp_m) then
        disp_m = d
        body = i
      end if
    end do
  end subroutine residual_displacement

  !> Opening of joint j at its intrados and extrados ends: distance of the left body's
  !> end points from the right body's face, positive when apart (`cs`: cos and sin of
  !> every body's rotation).
  pure function joint_gaps(mon, bodies, cs, j) result(gaps)
    type(monitor_t), intent(in) :: mon
    type(bodies_t), intent(in) :: bodies
    real(dp), intent(in) :: cs(:, :)
    integer, intent(in) :: j
    real(dp) :: gaps(2), pa(2), pb(2), nrm(2)
    integer :: a, b, e
    a = mon%joint_bodies(1, j)
    b = mon%joint_bodies(2, j)
    nrm = rotated(mon%joint_normal(:, j), cs(:, b))
    pb = material_point(bodies, cs, b, mon%joint_ends(:, 1, j))
    do e = 1, 2
      pa = material_point(bodies, cs, a, mon%joint_ends(:, e, j))
      gaps(e) = dot_product(pa - pb, nrm)
    end do
  end function joint_gaps

  !> Where the point of `body` that was at `x_ref` in the reference configuration is now.
  pure function material_point(bodies, cs, body, x_ref) result(x)
    type(bodies_t), intent(in) :: bodies
    real(dp), intent(in) :: cs(:, :)
    integer, intent(in) :: body
    real(dp), intent(in) :: x_ref(2)
    real(dp) :: x(2)
    x = bodies%q(1:2, body) + rotated(x_ref - bodies%q_ref(1:2, body), cs(:, body))
  end function material_point

  !> `p` turned by the rotation of cosine cs(1) and sine cs(2).
  pure function rotated(p, cs) result(r)
    real(dp), intent(in) :: p(2), cs(2)
    real(dp) :: r(2)
    r = [cs(1)*p(1) - cs(2)*p(2), cs(2)*p(1) + cs(1)*p(2)]
  end function rotated

  !> Record a hinge opening at `joint` (0..n) on `side` at `t_s`.
  subroutine add_hinge(mon, joint, side, t_s)
    type(monitor_t), intent(inout) :: mon
    integer, intent(in) :: joint, side
    real(dp), intent(in) :: t_s
    if (mon%n_hinges == size(mon%hinge_time_s)) then
      mon%hinge_time_s = [mon%hinge_time_s, mon%hinge_time_s]
      mon%hinge_joint = [mon%hinge_joint, mon%hinge_joint]
      mon%hinge_side = [mon%hinge_side, mon%hinge_side]
    end if
    mon%n_hinges = mon%n_hinges + 1
    mon%hinge_time_s(mon%n_hinges) = t_s
    mon%hinge_joint(mon%n_hinges) = joint
    mon%hinge_side(mon%n_hinges) = side
  end subroutine add_hinge

end module voussoir_monitors
