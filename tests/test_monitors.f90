!> The run monitors driven alone by block positions made by hand, no time loop.
!>
!> A flat "arch" of one square voussoir, [0, 1] x [0, 1] m, between two driven
!> foundations [-1, 0] x [0, 1] (body 2, the table body) and [1, 2] x [0, 1] (body 3):
!> joint 0 is the face x = 0, joint 1 the face x = 1, intrados end at y = 0, extrados end
!> at y = 1. Hinges open at a gap of 0.01 m, close below 0.005 m; a fall is a drop of
!> 0.25 m or a turn of 0.5 rad.
!>
!> Turning the voussoir by -phi (clockwise) about (0, 0) opens joint 0 at its extrados
!> end by sin(phi) while its intrados end stays shut: a hinge at joint 0 on the
!> intrados. Joint 1 then opens by 1 - cos(phi) at its intrados end and closes
!> (negative) at its extrados end: below half the hinge gap for phi = 0.05, no hinge.
!> Turning it by -phi about (1, 1) opens joint 1 at its intrados end by sin(phi), its
!> extrados end shut: a hinge at joint 1 on the extrados; joint 0 then has gaps
!> cos(phi) - sin(phi) - 1 and cos(phi) - 1, both negative: closed.
program test_monitors
  use voussoir_kinds, only: dp
  use voussoir_assembly, only: assembly_t, role_voussoir, role_foundation
  use voussoir_bodies, only: bodies_t
  use voussoir_hinge_side, only: side_intrados, side_extrados
  use voussoir_monitors, only: monitor_t, monitor_init, monitor_update, monitor_clear, crown_displacement, &
                               residual_displacement, joint_closed
  use voussoir_assert, only: assert_true, assert_close, assert_summary
  implicit none

  real(dp), parameter :: phi = 0.05_dp, hinge_gap_m = 0.01_dp
  type(assembly_t) :: flat
  type(bodies_t) :: bodies

  call make_flat_arch(flat, bodies)
  call test_joint_normals()
  call test_hinges()
  call test_collapse_by_drop()
  call test_collapse_by_rotation()
  call test_crown_and_residual_follow_the_table()
  call test_peak_joint_opening()
  call assert_summary()

contains

  subroutine make_flat_arch(arch, bodies)
    type(assembly_t), intent(out) :: arch
    type(bodies_t), intent(out) :: bodies
    arch%n_bodies = 3
    arch%n_voussoirs = 1
    arch%driven = [.false., .true., .true.]
    arch%role = [role_voussoir, role_foundation, role_foundation]
    allocate (arch%joint_bodies(2, 0:1), arch%joint_intrados_xy(2, 0:1), arch%joint_extrados_xy(2, 0:1))
    arch%joint_bodies(:, 0) = [2, 1]
    arch%joint_bodies(:, 1) = [1, 3]
    arch%joint_intrados_xy = reshape([0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp], [2, 2])
    arch%joint_extrados_xy = reshape([0.0_dp, 1.0_dp, 1.0_dp, 1.0_dp], [2, 2])
    bodies%n = 3
    bodies%q_ref = reshape([0.5_dp, 0.5_dp, 0.0_dp, -0.5_dp, 0.5_dp, 0.0_dp, 1.5_dp, 0.5_dp, 0.0_dp], [3, 3])
    bodies%q = bodies%q_ref
    bodies%driven = arch%driven
    bodies%role = arch%role
  end subroutine make_flat_arch

  !> The voussoir turned by `angle` [rad] about `pivot` from its reference place, then
  !> shifted by `shift` [m]; the foundations at rest.
  subroutine place_voussoir(pivot, angle, shift)
    real(dp), intent(in) :: pivot(2), angle, shift(2)
    real(dp) :: r(2)
    bodies%q = bodies%q_ref
    r = bodies%q_ref(1:2, 1) - pivot
    bodies%q(1:2, 1) = pivot + [cos(angle)*r(1) - sin(angle)*r(2), sin(angle)*r(1) + cos(angle)*r(2)] + shift
    bodies%q(3, 1) = angle
  end subroutine place_voussoir

  subroutine test_joint_normals()
    type(monitor_t) :: mon
    call monitor_init(flat, bodies, 0.25_dp, 0.5_dp, hinge_gap_m, mon)
    ! Both faces are vertical; the normal points from the right body to the left one: -x.
    call assert_true(mon%n_joints == 2, 'monitors: two joints for one voussoir')
    call assert_true(all(abs(mon%joint_normal - reshape([-1.0_dp, 0.0_dp, -1.0_dp, 0.0_dp], [2, 2])) < 1.0e-15_dp), &
                     'monitors: joint normals point from the right body to the left (-x)')
    call assert_true(all(mon%crown_bodies == [1]) .and. mon%table_body == 2, &
                     'monitors: the crown is the voussoir, the table the first driven body')
    call assert_true(all(mon%joint_state == joint_closed) .and. mon%n_hinges == 0 .and. .not. mon%collapsed, &
                     'monitors: every joint closed at the start, nothing seen')
  end subroutine test_joint_normals

  subroutine test_hinges()
    type(monitor_t) :: mon
    call monitor_init(flat, bodies, 0.25_dp, 0.5_dp, hinge_gap_m, mon)
    call place_voussoir([0.0_dp, 0.0_dp], -phi, [0.0_dp, 0.0_dp])   ! joint 0 opens by sin(0.05) = 0.05
    call monitor_update(mon, bodies, 0.1_dp)
    call assert_true(mon%n_hinges == 1, 'hinges: one hinge once joint 0 opens at its extrados')
    call assert_true(mon%hinge_joint(1) == 0 .and. mon%hinge_side(1) == side_intrados, &
                     'hinges: at joint 0, pivoting on the intrados')
    call assert_close(mon%hinge_time_s(1), 0.1_dp, 'hinges: opened at t = 0.1 s')
    call assert_true(mon%joint_state(2) == joint_closed, 'hinges: joint 1 (opened by 1 - cos(0.05) = 1.2 mm) stays closed')
    ! The crown's centroid, sqrt(1/2) m from the pivot, moved by the chord 2 sqrt(1/2) sin(phi/2).
    call assert_close(mon%peak_crown_disp_m, sqrt(2.0_dp)*sin(0.5_dp*phi), 'hinges: peak crown displacement', &
                      rtol=1.0e-12_dp)

    ! Partly shut (7.5 mm, between half the gap and the gap), then wide open again: the
    ! joint never closed, so no second hinge.
    call place_voussoir([0.0_dp, 0.0_dp], -asin(0.0075_dp), [0.0_dp, 0.0_dp])
    call monitor_update(mon, bodies, 0.2_dp)
    call assert_true(mon%joint_state(1) == side_intrados, 'hinges: at 7.5 mm joint 0 is still open (hysteresis)')
    call place_voussoir([0.0_dp, 0.0_dp], -phi, [0.0_dp, 0.0_dp])
    call monitor_update(mon, bodies, 0.3_dp)
    call assert_true(mon%n_hinges == 1, 'hinges: reopening a joint that never closed is not a new hinge')

    ! Shut, then open again: a second hinge at the same place.
    call place_voussoir([0.0_dp, 0.0_dp], 0.0_dp, [0.0_dp, 0.0_dp])
    call monitor_update(mon, bodies, 0.4_dp)
    call assert_true(mon%joint_state(1) == joint_closed, 'hinges: joint 0 closed at rest')
    call place_voussoir([0.0_dp, 0.0_dp], -phi, [0.0_dp, 0.0_dp])
    call monitor_update(mon, bodies, 0.5_dp)
    call assert_true(mon%n_hinges == 2, 'hinges: closed and reopened, a second hinge')
    call assert_close(mon%hinge_time_s(2), 0.5_dp, 'hinges: the second at t = 0.5 s')

    ! Turned about the extrados end of joint 1: joint 1 opens at its intrados end.
    call place_voussoir([1.0_dp, 1.0_dp], -phi, [0.0_dp, 0.0_dp])
    call monitor_update(mon, bodies, 0.6_dp)
    call assert_true(mon%n_hinges == 3, 'hinges: a third hinge')
    call assert_true(mon%hinge_joint(3) == 1 .and. mon%hinge_side(3) == side_extrados, &
                     'hinges: at joint 1, pivoting on the extrados')
    call assert_true(mon%joint_state(1) == joint_closed, 'hinges: joint 0 closed by that turn')
    call assert_true(.not. mon%collapsed, 'hinges: turns of 0.05 rad and drops of 26 mm are no collapse')

    ! What was seen is forgotten by monitor_clear; the joints keep their state.
    call monitor_clear(mon)
    call assert_true(mon%n_hinges == 0 .and. mon%peak_crown_disp_m == 0.0_dp, 'hinges: cleared')
    call assert_true(mon%joint_state(2) == side_extrados, 'hinges: clearing keeps the joints as they are')
  end subroutine test_hinges

  !> The largest opening of a joint, at either end, over the updates: sin(phi) at joint 0's
  !> extrados after the turn about (0, 0) (joint 1 opens only 1 - cos(phi)); a smaller
  !> turn after it leaves the peak; after monitor_clear, a turn of phi/2 about (1, 1)
  !> opens joint 1's intrados end by sin(phi/2).
  subroutine test_peak_joint_opening()
    type(monitor_t) :: mon
    call monitor_init(flat, bodies, 0.25_dp, 0.5_dp, hinge_gap_m, mon)
    call assert_true(mon%peak_joint_opening_m == 0.0_dp, 'opening: none at the start')
    call place_voussoir([0.0_dp, 0.0_dp], -phi, [0.0_dp, 0.0_dp])
    call monitor_update(mon, bodies, 0.1_dp)
    call assert_close(mon%peak_joint_opening_m, sin(phi), 'opening: joint 0 opened by sin(phi) [m]', rtol=1.0e-12_dp)
    call place_voussoir([0.0_dp, 0.0_dp], -0.5_dp*phi, [0.0_dp, 0.0_dp])
    call monitor_update(mon, bodies, 0.2_dp)
    call assert_close(mon%peak_joint_opening_m, sin(phi), 'opening: the peak stays when the joint half shuts', &
                      rtol=1.0e-12_dp)
    call monitor_clear(mon)
    call assert_true(mon%peak_joint_opening_m == 0.0_dp, 'opening: cleared')
    call place_voussoir([1.0_dp, 1.0_dp], -0.5_dp*phi, [0.0_dp, 0.0_dp])
    call monitor_update(mon, bodies, 0.3_dp)
    call assert_close(mon%peak_joint_opening_m, sin(0.5_dp*phi), 'opening: joint 1 opened by sin(phi/2) [m]', &
                      rtol=1.0e-12_dp)
  end subroutine test_peak_joint_opening

  subroutine test_collapse_by_drop()
    type(monitor_t) :: mon
    call monitor_init(flat, bodies, 0.25_dp, 0.5_dp, hinge_gap_m, mon)
    call assert_true(mon%collapse_time_s /= mon%collapse_time_s, 'collapse: no time (NaN) before a collapse')
    call place_voussoir([0.0_dp, 0.0_dp], 0.0_dp, [0.0_dp, -0.2_dp])
    call monitor_update(mon, bodies, 1.0_dp)
    call assert_true(.not. mon%collapsed, 'collapse: a drop of 0.2 m < 0.25 m is none')
    call place_voussoir([0.0_dp, 0.0_dp], 0.0_dp, [0.0_dp, -0.3_dp])
    call monitor_update(mon, bodies, 1.5_dp)
    call place_voussoir([0.0_dp, 0.0_dp], 0.0_dp, [0.0_dp, -0.4_dp])
    call monitor_update(mon, bodies, 2.0_dp)
    call assert_true(mon%collapsed, 'collapse: a drop of 0.3 m > 0.25 m')
    call assert_close(mon%collapse_time_s, 1.5_dp, 'collapse: the time of the first drop past the limit')
    call assert_close(mon%peak_crown_disp_m, 0.4_dp, 'collapse: peak crown displacement, the deepest drop', &
                      rtol=1.0e-14_dp)
    ! A pure drop opens no joint: both faces slide along each other.
    call assert_true(mon%n_hinges == 0, 'collapse: a vertical drop opens no hinge')
  end subroutine test_collapse_by_drop

  subroutine test_collapse_by_rotation()
    type(monitor_t) :: mon
    call monitor_init(flat, bodies, 0.25_dp, 0.5_dp, hinge_gap_m, mon)
    call place_voussoir(bodies%q_ref(1:2, 1), 0.4_dp, [0.0_dp, 0.0_dp])
    call monitor_update(mon, bodies, 1.0_dp)
    call assert_true(.not. mon%collapsed, 'collapse: a turn of 0.4 rad < 0.5 rad about the centroid is none')
    call place_voussoir(bodies%q_ref(1:2, 1), -0.6_dp, [0.0_dp, 0.0_dp])
    call monitor_update(mon, bodies, 2.0_dp)
    call assert_true(mon%collapsed, 'collapse: a turn of 0.6 rad > 0.5 rad either way')
    call assert_close(mon%collapse_time_s, 2.0_dp, 'collapse: at the turn')
  end subroutine test_collapse_by_rotation

  subroutine test_crown_and_residual_follow_the_table()
    type(monitor_t) :: mon
    real(dp) :: d(2), disp_m
    integer :: body
    call monitor_init(flat, bodies, 0.25_dp, 0.5_dp, hinge_gap_m, mon)
    ! Everything carried 0.25 m along x by the table (exact in binary): nothing moved relative to it.
    bodies%q = bodies%q_ref
    bodies%q(1, :) = bodies%q(1, :) + 0.25_dp
    d = crown_displacement(mon, bodies)
    call residual_displacement(mon, bodies, disp_m, body)
    call assert_true(all(abs(d) < 1.0e-15_dp), 'crown: carried by the table, no displacement')
    call assert_true(disp_m < 1.0e-15_dp .and. body == 0, 'residual: carried by the table, none (body 0)')
    ! The voussoir 30 mm further along and 40 mm down: 50 mm from its place on the table.
    bodies%q(1:2, 1) = bodies%q(1:2, 1) + [0.03_dp, -0.04_dp]
    d = crown_displacement(mon, bodies)
    call residual_displacement(mon, bodies, disp_m, body)
    call assert_close(d(1), 0.03_dp, 'crown: dx relative to the table', rtol=1.0e-12_dp)
    call assert_close(d(2), -0.04_dp, 'crown: dy', rtol=1.0e-12_dp)
    call assert_close(disp_m, 0.05_dp, 'residual: 50 mm', rtol=1.0e-12_dp)
    call assert_true(body == 1, 'residual: of the voussoir')
  end subroutine test_crown_and_residual_follow_the_table

end program test_monitors
