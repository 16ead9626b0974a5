!> The steps a run need not solve (src/run/rest_window.f90, the IDA's skip_at_rest).
!>
!> The windows, from a table acceleration made of straight pieces (the accelerogram
!> motion interpolates its samples linearly): 0, 1, 5, 1, 0, 2, 0 m/s2 one second apart,
!> stepped at 0.1 s, for a capacity of 3.9 m/s2. The lead ends before |a| first reaches
!> 0.9 x 3.9 = 3.51 m/s2: on the rise 1 + 4 (t - 1) that is t = 1.6275 s, first reached at
!> the step ending at 1.7 s (k = 17), so 16 steps ride. The tail starts after the last |a|
!> of 0.5 x 3.9 = 1.95 m/s2 or more: |a| >= 1.95 only on 4.975 <= t <= 5.025 s (and on the
!> fall from 5 to 1 before 2.76 s), so after the step ending at 5.0 s (k = 50).
!>
!> The physics, against the closed form of a slender block (b = 0.2 m, h = 1.0 m,
!> friction 0.7) on a table: it lifts off at a = (b / h) g = 0.2 g and slides only at
!> 0.7 g, so its static capacity is 0.2 g. Under the one-cycle sine pulse of
!> input/records/sine_pulse_0.3g.csv scaled to 0.15 g, below 0.9 x 0.2 g, it does not
!> move: every step rides (and the run ends, at rest, a quarter of a second after the
!> pulse), and the full solve moves it by less than a micrometre. Scaled
!> to 0.24 g it rocks; riding the lead and ending at rest must give the motion of the full
!> solve (the same peak and final place of the block, within the NLGS's tolerance).
program test_rest_window
  use voussoir_kinds, only: dp, g_m_s2
  use voussoir_status, only: status_t
  use voussoir_motion, only: motion_t, motion_accelerogram
  use voussoir_rest_window, only: rest_window_t, rest_window
  use voussoir_config, only: config_t, read_config
  use voussoir_assembly, only: assembly_t
  use voussoir_model, only: model_t
  use voussoir_simulation, only: run_result_t
  use voussoir_setup, only: run_config
  use voussoir_assert, only: assert_true, assert_close, assert_summary
  implicit none

  call windows()
  call block_below_capacity()
  call block_rocking()
  call assert_summary()

contains

  subroutine windows()
    type(motion_t) :: m
    type(rest_window_t) :: w
    m = motion_accelerogram([0.0_dp, 1.0_dp, 5.0_dp, 1.0_dp, 0.0_dp, 2.0_dp, 0.0_dp], 1.0_dp, 0.0_dp)
    w = rest_window(m, 0.1_dp, 70, 3.9_dp)
    call assert_true(w%lead_steps == 16, 'lead: the steps before |a| first reaches 0.9 of the capacity')
    call assert_true(w%tail_step == 50, 'tail: after the last |a| of half the capacity or more')
    w = rest_window(m, 0.1_dp, 70, 0.0_dp)
    call assert_true(w%lead_steps == 0, 'no capacity: no lead')
    call assert_true(w%tail_step == huge(1), 'no capacity: no tail')
    w = rest_window(m, 0.1_dp, 70, 100.0_dp)
    call assert_true(w%lead_steps == 70, 'a motion below 0.9 of the capacity throughout: every step rides')
    call assert_true(w%tail_step == 0, 'and the tail starts at once')
  end subroutine windows

  !> Run the block under the sine pulse at `scale`, with the static capacity `capacity`
  !> (0: every step solved).
  subroutine run_block(name, scale, capacity_m_s2, res, status)
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: scale, capacity_m_s2
    type(run_result_t), intent(out) :: res
    type(status_t), intent(inout) :: status
    type(config_t) :: cfg
    type(assembly_t) :: asm
    type(model_t) :: model
    integer :: u
    open (newunit=u, file=name//'.txt', status='replace', action='write')
    write (u, '(a)') 'block free'
    write (u, '(a)') '-0.1 0.0', ' 0.1 0.0', ' 0.1 1.0', '-0.1 1.0'
    write (u, '(a)') 'block driven'
    write (u, '(a)') '-1.0 -0.2', ' 1.0 -0.2', ' 1.0 0.0', '-1.0 0.0'
    close (u)
    open (newunit=u, file=name//'.csv', status='replace', action='write')
    write (u, '(a)') 't_s,accel_m_s2'
    ! One sine cycle of 0.3 g and period 0.5 s (as the input's record), then 5 s still.
    block
      integer :: k
      do k = 0, 550
        write (u, '(f6.2,a,es24.16)') 0.01_dp*k, ',', merge(0.3_dp*g_m_s2*sin(4*acos(-1.0_dp)*0.01_dp*k), &
                                                             0.0_dp, k <= 50)
      end do
    end block
    close (u)
    open (newunit=u, file=name//'.nml', status='replace', action='write')
    write (u, '(a)') "&arch polygon_file = '"//name//".txt', thickness_m = 0.2, width_m = 0.2, "// &
      'density_kg_m3 = 2000, friction = 0.7 /'
    write (u, '(a,es24.16,a)') "&motion waveform = 'accelerogram', record_file = '"//name//".csv', record_scale = ", &
      scale, ', lead_s = 0.2, rest_s = 0 /'
    write (u, '(a)') '&solver dt_s = 1e-4 /'
    write (u, '(a)') "&output file = '"//name//".h5', stop_after_collapse_s = -1 /"
    close (u)
    call read_config(name//'.nml', [character(len=8) :: 'arch', 'motion', 'solver', 'output'], cfg, status)
    if (.not. status%ok) return
    cfg%solver%rest_capacity_m_s2 = capacity_m_s2
    call run_config(cfg, asm, model, res, status)
  end subroutine run_block

  subroutine block_below_capacity()
    type(run_result_t) :: full, skip
    type(status_t) :: status
    call run_block('rest_below', 0.5_dp, 0.0_dp, full, status)
    call assert_true(status%ok, 'block at 0.15 g, every step solved: runs '//trim(status%message))
    call run_block('rest_below', 0.5_dp, 0.2_dp*g_m_s2, skip, status)
    call assert_true(status%ok, 'block at 0.15 g, capacity 0.2 g: runs '//trim(status%message))
    call assert_true(full%peak_crown_disp_m < 1.0e-6_dp, 'block at 0.15 g, below its uplift at 0.2 g: '// &
                     'the full solve does not move it')
    call assert_true(skip%rest_steps == skip%n_steps, 'block at 0.15 g, capacity 0.2 g: every step rides')
    call assert_true(skip%ended_at_rest .and. skip%n_steps < full%n_steps, &
                     'and the run ends, at rest, before its motion does')
    call assert_close(skip%peak_crown_disp_m, 0.0_dp, 'and the block stays on the table', atol=1.0e-12_dp)
  end subroutine block_below_capacity

  subroutine block_rocking()
    type(run_result_t) :: full, skip
    type(status_t) :: status
    real(dp) :: final_full(3), final_skip(3)
    call run_block('rest_rocking', 0.8_dp, 0.0_dp, full, status)
    call assert_true(status%ok, 'block at 0.24 g, every step solved: runs '//trim(status%message))
    call run_block('rest_rocking', 0.8_dp, 0.2_dp*g_m_s2, skip, status)
    call assert_true(status%ok, 'block at 0.24 g, capacity 0.2 g: runs '//trim(status%message))
    call assert_true(full%peak_crown_disp_m > 1.0e-3_dp, 'block at 0.24 g, above its uplift at 0.2 g: it rocks')
    call assert_true(skip%rest_steps > 0 .and. skip%rest_steps < skip%n_steps, &
                     'block at 0.24 g, capacity 0.2 g: the lead rides, the pulse is solved')
    call assert_close(skip%peak_crown_disp_m, full%peak_crown_disp_m, &
                      'block at 0.24 g: the peak of the full solve', rtol=1.0e-4_dp)
    call assert_true(skip%ended_at_rest .and. skip%n_steps < full%n_steps, &
                     'block at 0.24 g: the run ends once the block has settled')
    ! Where the block stands at the end, relative to the table (both at rest by then).
    final_full = full%q(:, 1, full%n_samples) - [full%table(1, full%n_samples), 0.0_dp, 0.0_dp]
    final_skip = skip%q(:, 1, skip%n_samples) - [skip%table(1, skip%n_samples), 0.0_dp, 0.0_dp]
    call assert_close(final_skip(1), final_full(1), 'block at 0.24 g: its final x on the table', atol=1.0e-6_dp)
    call assert_close(final_skip(3), final_full(3), 'block at 0.24 g: its final rotation', atol=1.0e-6_dp)
  end subroutine block_rocking

end program test_rest_window
