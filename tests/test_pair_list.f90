!> The broad phase's pair list (voussoir_contacts) is rebuilt only when the bodies have
!> moved relative to one another, not when the table carries them all.
!>
!> relative_motion_m against closed forms: a common translation is no motion; of two
!> bodies one of which moves by d, each has moved by d/2 from the middle of their
!> displacements; a rotation phi of a body of radius R is a motion of R |phi|.
!> And on the 180-degree seed arch: carried 20 alert distances along the table, the
!> list is kept, and the contacts found with it are those found with a list built anew;
!> one voussoir moved by an alert distance makes the list be rebuilt.
program test_pair_list
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t
  use voussoir_assembly, only: assembly_t, build_arch
  use voussoir_model, only: model_t, solver_settings_t
  use voussoir_contact_law, only: contact_law_t, pair_friction_t
  use voussoir_setup, only: init_model
  use voussoir_bodies, only: update_world_vertices
  use voussoir_contacts, only: contact_set_t, detect_contacts, relative_motion_m
  use voussoir_assert, only: assert_true, assert_close, assert_summary
  implicit none

  call closed_forms()
  call carried_arch()
  call assert_summary()

contains

  subroutine closed_forms()
    real(dp) :: q_ref(3, 3), q(3, 3), radius(3)
    real(dp), parameter :: d = 1.0e-3_dp, phi = 2.0e-3_dp
    q_ref = reshape([0.0_dp, 0.0_dp, 0.0_dp, 0.5_dp, 0.1_dp, 0.2_dp, 1.0_dp, 0.3_dp, -0.1_dp], [3, 3])
    radius = [0.1_dp, 0.2_dp, 0.3_dp]
    q = q_ref
    q(1, :) = q(1, :) + 0.3_dp
    q(2, :) = q(2, :) - 0.2_dp
    call assert_true(relative_motion_m(q, q_ref, radius) <= 1.0e-15_dp, 'a translation common to all bodies is no motion')
    q = q_ref
    q(1, 2) = q(1, 2) + d
    call assert_close(relative_motion_m(q, q_ref, radius), 0.5_dp*d, 'one of the bodies moved by d: d/2 from the middle', &
                      rtol=1.0e-9_dp)
    q = q_ref
    q(3, 3) = q(3, 3) + phi
    call assert_close(relative_motion_m(q, q_ref, radius), radius(3)*phi, 'a rotation phi of a body of radius R: R phi', &
                      rtol=1.0e-9_dp)
  end subroutine closed_forms

  subroutine carried_arch()
    type(assembly_t) :: arch
    type(model_t) :: model
    type(solver_settings_t) :: s
    type(status_t) :: status
    type(pair_friction_t) :: no_pairs(0)
    type(contact_set_t) :: fresh
    real(dp), allocatable :: q(:, :), built_at(:, :)
    real(dp) :: alert
    integer :: n0
    call build_arch(180.0_dp, 15, 0.508_dp, 0.071_dp, arch)
    call init_model(arch, 2000.0_dp, 0.1_dp, s, contact_law_t(friction=0.6_dp, pairs=no_pairs), model, status)
    call assert_true(status%ok, 'arch model: '//trim(status%message))
    alert = model%solver%alert_m
    call assert_true(alert > 0.0_dp, 'the model has an alert distance')
    associate (b => model%bodies, c => model%contacts)
      q = b%q
      call update_world_vertices(b, q)
      call detect_contacts(b, q, alert, model%law, c)
      n0 = c%n
      call assert_true(n0 == 32, 'the arch at rest: two contact points on each of its 16 joints')
      built_at = c%q_pairs
      ! Carried by the table.
      q(1, :) = q(1, :) + 20.0_dp*alert
      q(2, :) = q(2, :) + 5.0_dp*alert
      call update_world_vertices(b, q)
      call detect_contacts(b, q, alert, model%law, c)
      call assert_true(all(c%q_pairs == built_at), 'carried 20 alert distances: the pair list is kept')
      call detect_contacts(b, q, alert, model%law, fresh)
      call assert_true(c%n == n0 .and. fresh%n == n0, 'carried: the same contacts as with a list built anew')
      call assert_true(maxval(abs(c%gap_m(1:n0) - fresh%gap_m(1:n0))) <= 1.0e-12_dp, 'carried: the same gaps')
      ! One voussoir moved relative to the others.
      q(2, 8) = q(2, 8) + alert
      call update_world_vertices(b, q)
      call detect_contacts(b, q, alert, model%law, c)
      call assert_true(any(c%q_pairs /= built_at), 'a voussoir moved by an alert distance: the list is rebuilt')
    end associate
  end subroutine carried_arch

end program test_pair_list
