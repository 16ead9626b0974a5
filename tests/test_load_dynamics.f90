!> The loads of &load in voussoir-run's dynamics (voussoir_setup's apply_loads, the
!> bodies' external loads in the Moreau-Jean step), through the whole chain: a namelist
!> and a polygon file written here, read, built and stepped, on a table that does not move.
!>
!> Closed forms (a block b = 0.2 m wide, h = 1.0 m high, density 2000 kg/m3, width 0.2 m:
!> W = 784.8 N, on a fixed base):
!> - a horizontal point load P towards +x at the top corner (-b/2, h) tips the block
!>   about (b/2, 0) once P h > W b/2, P_tip = W b / (2 h) = 78.48 N (friction 0.7 >> P/W);
!>   at 1.1 P_tip the excess moment 0.1 P_tip h drives the inverted pendulum away
!>   (theta ~ 0.02 (cosh(3.8 t) - 1) rad: 0.4 rad after 1 s), at 0.9 P_tip it stands;
!> - the same load as a dead load (point_load_live = .false.) acts the same: a live load
!>   runs at load factor 1;
!> - a squat block (b = 1.0 m, h = 0.2 m, friction 0.3) pushed at mid-height slides once
!>   P > mu W (tipping needs W b / h = 5 W): at 1.1 mu W it slides off with
!>   a = 0.1 mu g = 0.29 m/s2 (0.15 m in 1 s), at 0.9 mu W it stays.
!> And held against the limit analysis (an independent, static method, itself checked
!> against a four-hinge enumeration in tests/limit/check_limit.py): a semicircular arch
!> of 16 voussoirs (R_ext 1 m, t 0.15 m, friction 0.6) under a constant vertical point load
!> on its extrados at x = -0.2 m collapses at 1.02 times the LP's load factor and stands
!> at 0.98 times it.
program test_load_dynamics
  use voussoir_kinds, only: dp, g_m_s2
  use voussoir_status, only: status_t
  use voussoir_config, only: config_t, read_config
  use voussoir_assembly, only: assembly_t
  use voussoir_model, only: model_t, model_step
  use voussoir_monitors, only: monitor_t
  use voussoir_setup, only: build_model
  use voussoir_assembly, only: build_arch
  use voussoir_load_config, only: load_config_t
  use voussoir_placed_loads, only: placed_loads_t, place_loads, top_surface
  use voussoir_block_interfaces, only: interface_set_t, find_interfaces
  use voussoir_limit_lp, only: block_loads_t, lp_result_t, block_loads, add_placed_loads, lp_capacity, &
                               nonassociative_capacity
  use voussoir_assert, only: assert_true, assert_close, assert_summary
  implicit none

  real(dp), parameter :: rho = 2000.0_dp, width = 0.2_dp

  call tipping(1.1_dp, .true., 'live')
  call tipping(0.9_dp, .false., 'live')
  call tipping(1.1_dp, .true., 'dead')
  call sliding(1.1_dp, .true.)
  call sliding(0.9_dp, .false.)
  call arch_point_load()
  call assert_summary()

contains

  !> Write a block b x h on a base and a namelist with the &load text; build the model;
  !> step for `seconds`; the block's final rotation [rad] and x displacement [m].
  subroutine run_block(name, b, h, mu, load_text, seconds, rotation_rad, shift_m, status)
    character(len=*), intent(in) :: name, load_text
    real(dp), intent(in) :: b, h, mu, seconds
    real(dp), intent(out) :: rotation_rad, shift_m
    type(status_t), intent(inout) :: status
    type(config_t) :: cfg
    type(assembly_t) :: asm
    type(model_t) :: model
    type(monitor_t) :: mon
    real(dp) :: duration_s, x0
    integer :: u, k
    open (newunit=u, file=name//'.txt', status='replace', action='write')
    write (u, '(a)') 'block free'
    write (u, '(2es24.16)') -b/2, 0.0_dp, b/2, 0.0_dp, b/2, h, -b/2, h
    write (u, '(a)') 'block driven'
    write (u, '(2es24.16)') -2.0_dp, -0.2_dp, 2.0_dp, -0.2_dp, 2.0_dp, 0.0_dp, -2.0_dp, 0.0_dp
    close (u)
    open (newunit=u, file=name//'.nml', status='replace', action='write')
    write (u, '(a,es24.16,a,es24.16,a,es24.16,a)') "&arch polygon_file = '"//name//".txt', thickness_m = ", &
      min(b, h), ', width_m = ', width, ', density_kg_m3 = 2000, friction = ', mu, ' /'
    write (u, '(a)') "&motion waveform = 'afd', amplitude_m = 0, frequency_hz = 1, rest_s = 1 /"
    write (u, '(a)') '&solver dt_s = 1e-3, tol = 1e-6 /'
    write (u, '(a)') "&output file = '"//name//".h5' /"
    write (u, '(a)') '&load '//load_text//' /'
    close (u)
    rotation_rad = 0.0_dp
    shift_m = 0.0_dp
    call read_config(name//'.nml', [character(len=8) :: 'arch', 'motion', 'solver', 'output', 'load'], cfg, status)
    if (.not. status%ok) return
    call build_model(cfg, asm, model, mon, duration_s, status)
    if (.not. status%ok) return
    x0 = model%bodies%q(1, 1)
    do k = 1, nint(seconds/model%solver%dt_s)
      call model_step(model, status)
      if (.not. status%ok) return
      if (abs(model%bodies%q(3, 1)) > 0.5_dp) exit   ! fallen far enough
    end do
    rotation_rad = model%bodies%q(3, 1)
    shift_m = model%bodies%q(1, 1) - x0
  end subroutine run_block

  subroutine tipping(factor, tips, kind)
    real(dp), intent(in) :: factor
    logical, intent(in) :: tips
    character(len=*), intent(in) :: kind
    real(dp), parameter :: b = 0.2_dp, h = 1.0_dp
    real(dp) :: w_n, p_n, rotation, shift
    type(status_t) :: status
    character(len=160) :: text, label
    w_n = rho*b*h*width*g_m_s2
    p_n = factor*w_n*b/(2*h)
    write (text, '(a,es24.16,a)') 'point_load_n(1) = ', p_n, ', point_load_dir_deg(1) = 0, point_load_x_m(1) = -0.1, '// &
      'point_load_y_m(1) = 1.0, point_load_live(1) = '//trim(merge('.true. ', '.false.', kind == 'live'))
    write (label, '(a,f4.2,a)') 'a '//kind//' point load of ', factor, ' x W b / (2 h) at the top corner'
    call run_block('load_tip_'//kind, b, h, 0.7_dp, trim(text), 1.0_dp, rotation, shift, status)
    call assert_true(status%ok, trim(label)//': runs '//trim(status%message))
    write (label, '(a,es10.3,a)') trim(label)//' (rotation ', rotation, ' rad)'
    if (tips) then
      ! Clockwise (negative) about the +x corner.
      call assert_true(rotation < -0.1_dp, trim(label)//': the block tips (rotation after 1 s < -0.1 rad)')
    else
      call assert_true(abs(rotation) < 1.0e-3_dp, trim(label)//': the block stands (|rotation| < 1e-3 rad)')
    end if
  end subroutine tipping

  subroutine sliding(factor, slides)
    real(dp), intent(in) :: factor
    logical, intent(in) :: slides
    real(dp), parameter :: b = 1.0_dp, h = 0.2_dp, mu = 0.3_dp
    real(dp) :: w_n, rotation, shift
    type(status_t) :: status
    character(len=160) :: text, label
    w_n = rho*b*h*width*g_m_s2
    write (text, '(a,es24.16,a)') 'point_load_n(1) = ', factor*mu*w_n, ', point_load_dir_deg(1) = 0, '// &
      'point_load_x_m(1) = -0.5, point_load_y_m(1) = 0.1'
    write (label, '(a,f4.2,a)') 'a point load of ', factor, ' x mu W at mid-height'
    call run_block('load_slide', b, h, mu, trim(text), 1.0_dp, rotation, shift, status)
    call assert_true(status%ok, trim(label)//': runs '//trim(status%message))
    write (label, '(a,es10.3,a)') trim(label)//' (x ', shift, ' m)'
    if (slides) then
      ! a = 0.1 mu g: 0.147 m in 1 s; half of it is enough to tell.
      call assert_true(shift > 0.07_dp, trim(label)//': the block slides (x after 1 s > 0.07 m)')
    else
      call assert_true(abs(shift) < 1.0e-4_dp, trim(label)//': the block stays (|x| < 0.1 mm)')
    end if
    call assert_true(abs(rotation) < 1.0e-3_dp, trim(label)//': without tipping')
  end subroutine sliding

  !> The non-associative load factor of 1 kN down at (x, top) on the arch, then the
  !> dynamics at 1.02 and 0.98 times it for 2 s: the crown falls (> 0.1 m) or stays (< 0.1 mm).
  subroutine arch_point_load()
    real(dp), parameter :: x = -0.2_dp, mu = 0.6_dp, factor(2) = [1.02_dp, 0.98_dp]
    type(assembly_t) :: arch
    type(load_config_t) :: d
    type(placed_loads_t) :: placed
    type(interface_set_t) :: faces
    type(block_loads_t) :: loads
    type(lp_result_t) :: assoc, nonassoc
    type(status_t) :: status
    real(dp) :: y, lambda, drop(2)
    real(dp), allocatable :: friction(:)
    integer :: blk, k, steps
    logical :: found, converged
    character(len=200) :: text
    call build_arch(180.0_dp, 16, 1.0_dp, 0.15_dp, arch)
    call top_surface(arch, x, y, blk, found)
    d%n_point_loads = 1
    d%point_load_n(1) = 1000.0_dp
    d%point_load_x_m(1) = x
    d%point_load_y_m(1) = y
    call find_interfaces(arch, 1.0e-9_dp, 0.0_dp, faces, status)
    call place_loads(d, arch, 0.0_dp, placed, status)
    call block_loads(arch, rho, 1.0_dp, g_m_s2, loads)
    call add_placed_loads(placed, loads)
    friction = spread(mu, 1, faces%n)
    call lp_capacity(arch, faces, loads, friction, 0.0_dp*friction, assoc, status)
    call nonassociative_capacity(arch, faces, loads, friction, assoc, nonassoc, steps, converged, status)
    call assert_true(status%ok .and. found .and. converged, 'arch with a point load: the LP solved')
    call assert_close(nonassoc%load_factor, assoc%load_factor, 'arch with a point load: hinging governs '// &
                      '(non-associative = associative)', rtol=1.0e-6_dp)
    lambda = nonassoc%load_factor
    do k = 1, 2
      write (text, '(a,es24.16,a,es24.16,a,es24.16)') 'point_load_n(1) = ', factor(k)*lambda*1000.0_dp, &
        ', point_load_x_m(1) = ', x, ', point_load_y_m(1) = ', y
      call run_arch(trim(text), drop(k), status)
      call assert_true(status%ok, 'arch with a point load: runs '//trim(status%message))
    end do
    write (text, '(a,f8.5,a,2es10.3,a)') 'arch, 1 kN x 1.02 and 0.98 of the LP load factor ', lambda, &
      ' at x = -0.2 m (largest drop ', drop, ' m)'
    call assert_true(drop(1) > 0.1_dp, trim(text)//': collapses at 1.02')
    call assert_true(drop(2) < 1.0e-4_dp, trim(text)//': stands at 0.98')
  end subroutine arch_point_load

  !> The arch of arch_point_load from a namelist with &load `load_text`, run for 2 s: the
  !> largest drop of a voussoir's centroid [m].
  subroutine run_arch(load_text, drop_m, status)
    character(len=*), intent(in) :: load_text
    real(dp), intent(out) :: drop_m
    type(status_t), intent(inout) :: status
    type(config_t) :: cfg
    type(assembly_t) :: asm
    type(model_t) :: model
    type(monitor_t) :: mon
    real(dp) :: duration_s
    real(dp), allocatable :: y0(:)
    integer :: u, k
    open (newunit=u, file='load_arch.nml', status='replace', action='write')
    write (u, '(a)') '&arch embrace_deg = 180, n_voussoirs = 16, r_ext_m = 1.0, thickness_m = 0.15, width_m = 1.0,'
    write (u, '(a)') '  density_kg_m3 = 2000, friction = 0.6 /'
    write (u, '(a)') "&motion waveform = 'afd', amplitude_m = 0, frequency_hz = 1, rest_s = 2 /"
    write (u, '(a)') '&solver dt_s = 1e-3 /'
    write (u, '(a)') "&output file = 'load_arch.h5' /"
    write (u, '(a)') '&load '//load_text//' /'
    close (u)
    drop_m = 0.0_dp
    call read_config('load_arch.nml', [character(len=8) :: 'arch', 'motion', 'solver', 'output', 'load'], cfg, status)
    if (.not. status%ok) return
    call build_model(cfg, asm, model, mon, duration_s, status)
    if (.not. status%ok) return
    y0 = model%bodies%q(2, 1:16)
    do k = 1, nint(2.0_dp/model%solver%dt_s)
      call model_step(model, status)
      if (.not. status%ok) return
      drop_m = maxval(y0 - model%bodies%q(2, 1:16))
      if (drop_m > 0.1_dp) exit
    end do
  end subroutine run_arch

end program test_load_dynamics
