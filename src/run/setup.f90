!> From a validated configuration to a model ready to run.
module voussoir_setup
  use voussoir_kinds, only: dp, g_m_s2
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: fmt_significant, itoa
  use voussoir_config, only: config_t, waveform_afd, waveform_ramp, waveform_record, waveform_accelerogram, has_loads
  use voussoir_placed_loads, only: placed_loads_t, place_loads, fill_column, kind_fill
  use voussoir_assembly, only: assembly_t, role_fill, role_backing
  use voussoir_config_assembly, only: build_config_assembly
  use voussoir_geometry, only: polygon_min_width
  use voussoir_bodies, only: bodies_t, bodies_init, add_point_load, add_carried_mass
  use voussoir_model, only: model_t, solver_settings_t
  use voussoir_coarse, only: coarse_init
  use voussoir_contact_law, only: contact_law_t, contact_law_init
  use voussoir_motion, only: motion_t, motion_afd, motion_ramp, motion_record, motion_accelerogram, motion_duration_s, &
                             motion_set_vertical_ratio, motion_set_vertical_record
  use voussoir_ground_record, only: ground_record_t, read_ground_record
  use voussoir_monitors, only: monitor_t, monitor_init
  use voussoir_simulation, only: run_result_t, simulate
  implicit none
  private

  public :: build_model, run_config, init_model, automatic_alert_m

  !> Relative difference of the vertical record's time step from the horizontal's allowed.
  real(dp), parameter :: vertical_dt_tol = 1.0e-6_dp

contains

  !> The assembly, model and monitors that `cfg` describes, and the time to simulate
  !> (its record's size checked with or without the contacts, `record_contacts`).
  subroutine build_model(cfg, assembly, model, mon, duration_s, status, record_contacts)
    type(config_t), intent(in) :: cfg
    type(assembly_t), intent(out) :: assembly
    type(model_t), intent(out) :: model
    type(monitor_t), intent(out) :: mon
    real(dp), intent(out) :: duration_s
    type(status_t), intent(inout) :: status
    logical, intent(in), optional :: record_contacts
    logical :: with_contacts
    type(solver_settings_t) :: settings
    type(contact_law_t) :: law
    type(ground_record_t) :: rec
    real(dp) :: hinge_gap_m, collapse_drop_m, size_m
    integer :: k

    duration_s = 0.0_dp
    associate (a => cfg%arch, m => cfg%motion, s => cfg%solver)
      call build_config_assembly(cfg, assembly, status)
      if (.not. status%ok) then
        status%message = trim(cfg%source_file)//': '//trim(status%message)
        return
      end if
      settings%dt_s = s%dt_s
      settings%theta = s%theta
      settings%tol = s%tol
      settings%max_iter = s%max_iter
      settings%allow_nonconvergence = s%allow_nonconvergence
      settings%alert_m = s%alert_m
      settings%rest_capacity_m_s2 = s%rest_capacity_m_s2
      call contact_law_init(a%friction, a%contact_inset_m, a%joint_friction, assembly, law, status)
      if (.not. status%ok) then
        status%message = trim(cfg%source_file)//': &arch '//trim(status%message)
        return
      end if
      call init_model(assembly, a%density_kg_m3, a%width_m, settings, law, model, status)
      if (.not. status%ok) return
      if (has_loads(cfg) .or. assembly%has_fill) call apply_loads(cfg, assembly, model%bodies, status)
      if (.not. status%ok) return
      if (s%coarse_correction .and. allocated(assembly%course)) &
        call coarse_init(model%coarse, assembly%course, model%bodies%inv_mass, model%bodies%inv_inertia)

      select case (m%waveform)
      case (waveform_afd)
        model%motion = motion_afd(m%frequency_hz, m%amplitude_m, m%n_attack, m%n_full, m%n_decay, &
                                  m%table_gain, m%table_delay_s)
        if (m%vertical_ratio /= 0.0_dp) call motion_set_vertical_ratio(model%motion, m%vertical_ratio)
      case (waveform_ramp)
        model%motion = motion_ramp(m%ramp_rate_m_s3)
      case (waveform_record)
        call motion_record(trim(m%record_file), m%record_cutoff_hz, model%motion, status)
        if (.not. status%ok) return
      case (waveform_accelerogram)
        call read_ground_record(trim(m%record_file), rec, status)
        if (.not. status%ok) then
          status%message = trim(cfg%source_file)//': &motion record_file: '//trim(status%message)
          return
        end if
        call accelerogram_motion(cfg, rec, model%motion, status)
        if (.not. status%ok) return
      case default
        call fail(status, 'unknown waveform '//trim(m%waveform))
        return
      end select
      model%motion%start_s = m%lead_s
      duration_s = m%duration_s
      ! The lead is in the motion's end (its start), the rest comes after it.
      if (duration_s == 0.0_dp) duration_s = motion_duration_s(model%motion) + m%rest_s
      if (duration_s <= 0.0_dp) then
        call fail(status, trim(cfg%source_file)//': nothing to simulate: set &motion lead_s, rest_s or duration_s > 0')
        return
      end if
      with_contacts = .false.
      if (present(record_contacts)) with_contacts = record_contacts
      call check_work(cfg, duration_s, assembly%n_bodies, model%motion, with_contacts, status)
      if (.not. status%ok) return
    end associate
    ! Monitors left automatic (0) follow the size of the blocks: the ring's thickness, or
    ! for a polygon assembly the smallest width of its free blocks. Hinges open at 1 % of
    ! it, a block has fallen when it drops by half of it.
    size_m = cfg%arch%thickness_m
    if (assembly%n_voussoirs == 0) then
      size_m = huge(1.0_dp)
      do k = 1, assembly%n_bodies
        if (assembly%driven(k) .or. assembly%role(k) == role_fill .or. assembly%role(k) == role_backing) cycle   ! (not watched)
        size_m = min(size_m, polygon_min_width(assembly%polygon(k)%xy))
      end do
    end if
    hinge_gap_m = cfg%output%hinge_gap_m
    if (hinge_gap_m == 0.0_dp) hinge_gap_m = 0.01_dp*size_m
    collapse_drop_m = cfg%output%collapse_drop_m
    if (collapse_drop_m == 0.0_dp) collapse_drop_m = 0.5_dp*size_m
    call monitor_init(assembly, model%bodies, collapse_drop_m, cfg%output%collapse_rotation_rad, hinge_gap_m, mon)
  end subroutine build_model

  !> The accelerogram of &motion from its record `rec`: scaled, its horizontal played with
  !> `record_polarity`, and its vertical component (a record on the same time steps, or
  !> `vertical_ratio` times the horizontal record as recorded, so that a reversed record
  !> is the motion mirrored left-right).
  subroutine accelerogram_motion(cfg, rec, motion, status)
    type(config_t), intent(in) :: cfg
    type(ground_record_t), intent(in) :: rec
    type(motion_t), intent(out) :: motion
    type(status_t), intent(inout) :: status
    type(ground_record_t) :: vertical
    character(len=:), allocatable :: what
    associate (m => cfg%motion)
      if (m%record_polarity == -1) then
        motion = motion_accelerogram(-(m%record_scale*rec%accel_m_s2), rec%dt_s, m%lead_s)
      else
        motion = motion_accelerogram(m%record_scale*rec%accel_m_s2, rec%dt_s, m%lead_s)
      end if
      motion%record_name = rec%name
      motion%record_description = rec%description
      if (m%vertical_ratio /= 0.0_dp) then
        call motion_set_vertical_record(motion, m%vertical_ratio*(m%record_scale*rec%accel_m_s2))
      else if (len_trim(m%record_vertical_file) > 0) then
        what = trim(cfg%source_file)//': &motion record_vertical_file: '
        call read_ground_record(trim(m%record_vertical_file), vertical, status)
        if (.not. status%ok) then
          status%message = what//trim(status%message)
          return
        end if
        if (abs(vertical%dt_s - rec%dt_s) > vertical_dt_tol*rec%dt_s .or. &
            size(vertical%accel_m_s2) /= size(rec%accel_m_s2)) then
          call fail(status, what//trim(m%record_vertical_file)//' has '//itoa(size(vertical%accel_m_s2))// &
                    ' samples '//fmt_significant(vertical%dt_s, 6)//' s apart, the horizontal record_file '// &
                    itoa(size(rec%accel_m_s2))//' samples '//fmt_significant(rec%dt_s, 6)//' s apart: '// &
                    'the two components of one recording have the same time steps')
          return
        end if
        call motion_set_vertical_record(motion, m%record_scale*vertical%accel_m_s2)
      end if
    end associate
  end subroutine accelerogram_motion

  !> Refuse a run whose step count or stored record is out of reach, before it starts:
  !> at most `max_steps` steps, and at most `max_record_bytes` of samples in memory; and
  !> a record (or accelerogram) of absurd motion.
  subroutine check_work(cfg, duration_s, n_bodies, motion, with_contacts, status)
    type(config_t), intent(in) :: cfg
    real(dp), intent(in) :: duration_s
    integer, intent(in) :: n_bodies
    type(motion_t), intent(in) :: motion
    logical, intent(in) :: with_contacts
    type(status_t), intent(inout) :: status
    real(dp), parameter :: max_steps = 1.0e8_dp, max_record_bytes = 4.0e9_dp
    real(dp) :: steps, bytes
    character(len=:), allocatable :: f
    f = trim(cfg%source_file)
    call check_record(cfg, motion, status)
    if (.not. status%ok) return
    steps = duration_s/cfg%solver%dt_s
    if (.not. (steps <= max_steps)) then
      call fail(status, f//': the run would take '//fmt_significant(steps, 3)//' steps (simulated time '// &
                fmt_significant(duration_s, 4)//' s from &motion duration_s, lead_s, rest_s and the motion, '// &
                'over &solver dt_s = '// &
                fmt_significant(cfg%solver%dt_s, 4)//' s): more than the limit of 1e8; shorten the motion or raise dt_s')
      return
    end if
    ! Stored per sample: the bodies' x, y, rotation (24 bytes each) and, when recorded,
    ! their loaded contact points (about 4 per body, 60 bytes each); per step: time,
    ! norm, iterations.
    bytes = (24.0_dp + merge(240.0_dp, 0.0_dp, with_contacts))*n_bodies*steps/cfg%output%every + 24.0_dp*steps
    if (bytes > max_record_bytes) &
      call fail(status, f//': the run would keep '//fmt_significant(bytes/1.0e9_dp, 3)//' GB of samples in memory ('// &
                fmt_significant(steps, 3)//' steps, '//itoa(n_bodies)//' bodies, &output every = '//itoa(cfg%output%every)// &
                '): more than 4 GB; raise &output every or dt_s')
  end subroutine check_work

  !> A record's table acceleration (record: the second derivative of its filtered
  !> table_x_m; accelerogram: record_scale times its samples) is at most 1000 g, as the
  !> afd amplitude is (config_validate.f90: a bound on typos and wrong units, far above
  !> any shake table or earthquake), and a record's table_x_m at most 1000 m (the extent
  !> of any assembly). An absurd record ended in "NaN in the contact solve at step 1".
  subroutine check_record(cfg, motion, status)
    type(config_t), intent(in) :: cfg
    type(motion_t), intent(in) :: motion
    type(status_t), intent(inout) :: status
    real(dp), parameter :: max_accel_g = 1000.0_dp, max_x_m = 1000.0_dp
    character(len=:), allocatable :: what, source
    if (cfg%motion%waveform /= waveform_record .and. cfg%motion%waveform /= waveform_accelerogram) return
    source = 'record_scale times the samples'
    if (cfg%motion%waveform == waveform_record) source = 'the filtered table_x_m, twice derived'
    what = trim(cfg%source_file)//": &motion record_file = '"//trim(cfg%motion%record_file)//"': "
    if (cfg%motion%waveform == waveform_record) then
      if (.not. all(abs(motion%x_m) <= max_x_m)) then
        call fail(status, what//'its table_x_m (peak '//fmt_significant(maxval(abs(motion%x_m)), 4)// &
                  ' m from the first sample) is outside the allowed range |table_x_m| <= 1000 m')
        return
      end if
    end if
    if (allocated(motion%ay_m_s2)) then
      if (.not. all(abs(motion%ay_m_s2) <= max_accel_g*g_m_s2)) &
        call fail(status, trim(cfg%source_file)//': &motion vertical table acceleration (peak '// &
                  fmt_significant(maxval(abs(motion%ay_m_s2)), 4)//' m/s2) is outside the allowed range '// &
                  '|acceleration| <= 1000 g (check the units of record_vertical_file)')
    end if
    if (.not. all(abs(motion%a_m_s2) <= max_accel_g*g_m_s2)) &
      call fail(status, what//'its table acceleration (peak '//fmt_significant(maxval(abs(motion%a_m_s2)), 4)// &
                ' m/s2) is outside the allowed range |acceleration| <= 1000 g = '// &
                fmt_significant(max_accel_g*g_m_s2, 5)//' m/s2 ('//source//'; check the units)')
  end subroutine check_record

  !> A model of `assembly` at rest with the given solver settings and contact law and no
  !> table motion (set `model%motion` afterwards); an alert distance of 0 is made automatic.
  subroutine init_model(assembly, density_kg_m3, width_m, settings, law, model, status)
    type(assembly_t), intent(in) :: assembly
    real(dp), intent(in) :: density_kg_m3, width_m
    type(solver_settings_t), intent(in) :: settings
    type(contact_law_t), intent(in) :: law
    type(model_t), intent(out) :: model
    type(status_t), intent(inout) :: status
    call bodies_init(assembly, density_kg_m3, width_m, model%bodies, status)
    if (.not. status%ok) return
    if (assembly%has_fill) call add_fill_mass(assembly, model%bodies)
    model%solver = settings
    model%law = law
    if (.not. allocated(model%law%pairs)) allocate (model%law%pairs(0))
    if (settings%alert_m == 0.0_dp) model%solver%alert_m = automatic_alert_m(model%bodies)
  end subroutine init_model

  !> With a fill (&bridge), each free block carries the fill column over its top faces
  !> (the columns whose weight the LP places, `fill_column`) as mass that moves with it:
  !> the column's mass and its own moment of inertia, at its own centroid, added to the
  !> block's (docs/bridges.md, "Fill in the dynamics").
  subroutine add_fill_mass(assembly, bodies)
    type(assembly_t), intent(in) :: assembly
    type(bodies_t), intent(inout) :: bodies
    real(dp) :: area_m2, centroid_xy(2), polar_m4, mass_per_area_kg_m2
    integer :: k
    mass_per_area_kg_m2 = assembly%fill_weight_n_m2/g_m_s2   ! density x width
    do k = 1, assembly%n_bodies
      if (assembly%driven(k)) cycle
      call fill_column(assembly, k, area_m2, centroid_xy, polar_m4)
      if (area_m2 > 0.0_dp) call add_carried_mass(bodies, k, mass_per_area_kg_m2*area_m2, centroid_xy, &
                                                  mass_per_area_kg_m2*polar_m4)
    end do
  end subroutine add_fill_mass

  !> The loads of &load as constant forces at points of the blocks: dead loads, and live
  !> loads at load factor 1, where &load puts them (a path's positions are not run: its
  !> live loads stand at their own x, on the top surface). Loads on driven blocks go to
  !> the table. With a fill (&bridge), its active horizontal pressure (with an angle of
  !> friction) as constant forces; its weight is gravity on the mass each block carries
  !> (add_fill_mass), not a force here (docs/bridges.md).
  subroutine apply_loads(cfg, assembly, bodies, status)
    type(config_t), intent(in) :: cfg
    type(assembly_t), intent(in) :: assembly
    type(bodies_t), intent(inout) :: bodies
    type(status_t), intent(inout) :: status
    type(placed_loads_t) :: placed
    integer :: k
    call place_loads(cfg%load, assembly, 0.0_dp, placed, status)
    if (.not. status%ok) then
      status%message = trim(cfg%source_file)//': '//trim(status%message)
      return
    end if
    do k = 1, placed%n
      if (placed%kind(k) == kind_fill) cycle     ! the fill's weight: its mass, under gravity
      if (.not. bodies%driven(placed%block(k))) &
        call add_point_load(bodies, placed%block(k), placed%xy(:, k), placed%force_n(:, k))
    end do
    ! The fill's horizontal pressure at rest: its active bound (the least the fill presses).
    do k = 1, placed%n_pressure
      if (.not. bodies%driven(placed%pressure_block(k))) &
        call add_point_load(bodies, placed%pressure_block(k), placed%pressure_xy(:, k), &
                            placed%pressure_lo_n(k)*placed%pressure_dir(:, k))
    end do
  end subroutine apply_loads

  !> Default alert distance: 4 % of the smallest free body's circumradius.
  pure real(dp) function automatic_alert_m(bodies)
    type(bodies_t), intent(in) :: bodies
    integer :: i
    automatic_alert_m = huge(1.0_dp)
    do i = 1, bodies%n
      if (.not. bodies%driven(i)) automatic_alert_m = min(automatic_alert_m, 0.04_dp*bodies%radius_m(i))
    end do
    if (automatic_alert_m == huge(1.0_dp)) automatic_alert_m = 1.0e-3_dp
  end function automatic_alert_m

  !> Build and run the simulation `cfg` describes; keep the contacts of every sample with
  !> `record_contacts` (voussoir-run does, for its file).
  subroutine run_config(cfg, assembly, model, res, status, record_contacts)
    type(config_t), intent(in) :: cfg
    type(assembly_t), intent(out) :: assembly
    type(model_t), intent(out) :: model
    type(run_result_t), intent(out) :: res
    type(status_t), intent(inout) :: status
    logical, intent(in), optional :: record_contacts
    type(monitor_t) :: mon
    real(dp) :: duration_s
    logical :: with_contacts
    with_contacts = .false.
    if (present(record_contacts)) with_contacts = record_contacts
    call build_model(cfg, assembly, model, mon, duration_s, status, with_contacts)
    if (.not. status%ok) return
    call simulate(model, mon, duration_s, cfg%output%every, cfg%output%stop_after_collapse_s, res, status, &
                  with_contacts)
  end subroutine run_config

end module voussoir_setup
