!> The &bridge group: a masonry arch bridge described as an engineer gives it (spans and
!> rises, the intrados shape, the ring, piers and abutments, and the material of each
!> part) instead of the &arch builder or a polygon file. Input only: the blocks are built
!> by voussoir_bridge (src/assembly/bridge.f90). Every refusal that follows from the values
!> alone is made here, when the file is read: it names the file, the group, the variable,
!> the value, the allowed range and why. docs/bridges.md.
module voussoir_bridge_config
  use voussoir_kinds, only: dp, pi
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa, fmt_real, fmt_significant, lower
  use voussoir_namelist_group, only: nml_group_t, checked_apart
  use voussoir_input_range, only: need
  use voussoir_bridge_shape, only: intrados_t, intrados_init, springing_reach, crown_extrados_m, shape_names, &
    shape_segmental, &
    shape_semicircular, shape_elliptical, shape_three_centred, shape_pointed, shape_parabolic, &
    three_centred_min_rise_ratio
  implicit none
  private
  public :: bridge_config_t, bridge_group, read_bridge_config, bridge_intrados, max_spans, bridge_length_m
  public :: fill_model_columns, fill_model_particles, max_fill_particles, max_rings
  public :: dispersion_angle, dispersion_boussinesq

  integer, parameter :: max_spans = 8
  integer, parameter :: max_bridge_voussoirs = 200     !! per span, as voussoir-limit's arch
  !> A ring deeper than this fraction of its span is more a wall pierced by an opening than
  !> an arch (and its springing joints reach over its piers).
  real(dp), parameter :: max_ring_over_span = 0.25_dp
  !> The fill's models: the engineers' columns (weight, spread and pressure in the LP, mass
  !> the voussoirs carry in the dynamics) or an assembly of particles (docs/bridges.md).
  character(len=*), parameter :: fill_model_columns = 'columns', fill_model_particles = 'particles'
  character(len=16), parameter :: fill_model_names(2) = [character(len=16) :: fill_model_columns, &
                                                         fill_model_particles]
  !> How a live load spreads through the columns' fill: uniformly between two lines at
  !> dispersion_angle_deg, or by Flamant's solution of Boussinesq's problem (docs/bridges.md).
  character(len=*), parameter :: dispersion_angle = 'angle', dispersion_boussinesq = 'boussinesq'
  character(len=16), parameter :: dispersion_names(2) = [character(len=16) :: dispersion_angle, &
                                                         dispersion_boussinesq]
  !> At most this many particles (estimated from the bridge's length x the fill's level).
  integer, parameter :: max_fill_particles = 20000
  real(dp), parameter :: default_course_m = 0.3_dp     !! the backing's courses when backing_course_m is not given
  !> At most this many rings (brick arches are built of a few half-brick rings).
  integer, parameter :: max_rings = 6
  !> ring_joint_friction not given: ring_friction stands in for it.
  real(dp), parameter :: unset_ring_joint_friction = -huge(1.0_dp)

  !> &bridge (no span given: no bridge).
  type :: bridge_config_t
    character(len=16) :: shape = shape_segmental        !! the intrados of every span, one of shape_names
    real(dp) :: span_m(max_spans) = 0.0_dp              !! clear span k between its intrados springings [m]; 0: no span
    real(dp) :: rise_m(max_spans) = 0.0_dp              !! rise of span k's intrados above its springings [m]
    real(dp) :: ring_thickness_m = 0.45_dp              !! ring depth, normal to the intrados [m]
    !> The ring as n_rings concentric rings of equal depth, their joints aligned; the
    !> interfaces between two rings (no tension, Coulomb) take ring_joint_friction.
    integer :: n_rings = 1
    real(dp) :: ring_joint_friction = unset_ring_joint_friction  !! (unset: ring_friction)
    integer :: n_voussoirs = 16                         !! voussoirs of each span, equal lengths along the intrados
    real(dp) :: pier_width_m = 1.0_dp                   !! between the intrados springings of the spans it carries [m]
    real(dp) :: pier_height_m = 2.0_dp                  !! the springings above the ground [m]
    real(dp) :: abutment_width_m = 1.0_dp               !! from an outer intrados springing back to the abutment's end [m]
    real(dp) :: width_m = 1.0_dp                        !! barrel width, out of plane [m]
    real(dp) :: ring_density_kg_m3 = 2000.0_dp
    real(dp) :: ring_friction = 0.6_dp                  !! Coulomb coefficient of the ring's joints
    real(dp) :: pier_density_kg_m3 = 2000.0_dp
    real(dp) :: pier_friction = 0.6_dp                  !! of a pier on the ground and under its springings
    real(dp) :: abutment_friction = 0.6_dp              !! of a skewback under its springing
    !> The fill (the engineers' model, voussoir-limit only): a level surface fill_level_m
    !> above the springings, its weight as vertical dead loads on the blocks beneath, and
    !> live loads spread through it at dispersion_angle_deg from the vertical either side.
    real(dp) :: fill_density_kg_m3 = 0.0_dp             !! 0: no fill
    real(dp) :: fill_level_m = 0.0_dp                   !! the fill's (and the road's) surface above the springings [m]
    real(dp) :: dispersion_angle_deg = 0.0_dp           !! 0: a live load acts on the extrados straight beneath it
    character(len=16) :: dispersion = dispersion_angle  !! one of dispersion_names
    !> The fill's horizontal pressure on the ring (Rankine, angle of friction phi): at least
    !> active, K_a = tan^2(45 - phi/2), up to passive_mobilisation x K_p = tan^2(45 + phi/2)
    !> where the ring moves into the fill; 0: no horizontal pressure.
    real(dp) :: fill_friction_deg = 0.0_dp
    real(dp) :: passive_mobilisation = 0.0_dp           !! the fraction of K_p mobilised (0: active only)
    !> The fill as particles instead (fill_model = 'particles'): the region between the
    !> abutments' tops, the extrados and the level cut into convex blocks of about
    !> fill_particle_size_m, free, of the fill's density, with Coulomb friction
    !> fill_particle_friction and no tension, ending in free faces at the abutments' backs.
    character(len=16) :: fill_model = fill_model_columns
    real(dp) :: fill_particle_size_m = 0.0_dp           !! [m]; 0: not given (particles need it)
    real(dp) :: fill_particle_friction = 0.6_dp         !! Coulomb coefficient of the particles
    !> Masonry backing over the haunches (docs/bridges.md, "Backing"): the region between
    !> the abutments' and piers' tops, the extrados and backing_level_m, in horizontal
    !> courses of backing_course_m, free blocks of backing_density_kg_m3 with Coulomb
    !> friction backing_friction and no tension.
    !> Compressive strength of each part [Pa] for the LP's crushing (0: rigid); an interface
    !> takes the lesser of its two blocks'. &limit compressive_strength_pa gives every
    !> interface one instead.
    real(dp) :: ring_compressive_strength_pa = 0.0_dp
    real(dp) :: pier_compressive_strength_pa = 0.0_dp
    real(dp) :: backing_compressive_strength_pa = 0.0_dp
    real(dp) :: backing_level_m = 0.0_dp                !! above the springings [m]; 0: no backing
    real(dp) :: backing_course_m = 0.0_dp               !! the courses' height [m]; 0: not given (0.3 m)
    real(dp) :: backing_density_kg_m3 = 2000.0_dp
    real(dp) :: backing_friction = 0.6_dp               !! Coulomb coefficient of the backing's joints
    integer :: n_spans = 0                              !! (derived) the spans given
  end type bridge_config_t

contains

  !> The &bridge table over `b`.
  subroutine bridge_group(b, g)
    type(bridge_config_t), intent(inout), target :: b
    type(nml_group_t), intent(out) :: g
    g%name = 'bridge'
    call g%add('shape', b%shape, choices=shape_names)
    call g%add('span_m', b%span_m, unset=0.0_dp, unit='m', range='0 < span_m <= 200 m', &
               about='real, m, the clear span k between its intrados springings')
    call g%add('rise_m', b%rise_m, unset=0.0_dp, unit='m', range='0 < rise_m <= 200 m', &
               about='real, m, the rise of span k (semicircular: may be left out)')
    call g%add('ring_thickness_m', b%ring_thickness_m, unit='m', range='0 < ring_thickness_m <= 10 m')
    call g%add('n_rings', b%n_rings, range='1 <= n_rings <= '//itoa(max_rings), when=checked_apart, &
               about='integer, concentric rings of equal depth sharing ring_thickness_m')
    call g%add('n_voussoirs', b%n_voussoirs, range='3 <= n_voussoirs <= '//itoa(max_bridge_voussoirs), &
               about='integer, per span')
    call g%add('pier_width_m', b%pier_width_m, unit='m', range='0 < pier_width_m <= 100 m')
    call g%add('pier_height_m', b%pier_height_m, unit='m', range='0 < pier_height_m <= 100 m')
    call g%add('abutment_width_m', b%abutment_width_m, unit='m', range='0 < abutment_width_m <= 100 m')
    call g%add('width_m', b%width_m, unit='m', range='0 < width_m <= 1000 m')
    call g%add('ring_density_kg_m3', b%ring_density_kg_m3, unit='kg/m3', range='0 < ring_density_kg_m3 <= 1e5')
    call g%add('ring_friction', b%ring_friction, range='ring_friction >= 0 (finite)')
    call g%add('ring_joint_friction', b%ring_joint_friction, range='ring_joint_friction >= 0 (finite)', &
               unset=unset_ring_joint_friction, &
               about='real, the Coulomb coefficient between two rings, with n_rings > 1 (default: ring_friction)')
    call g%add('pier_density_kg_m3', b%pier_density_kg_m3, unit='kg/m3', range='0 < pier_density_kg_m3 <= 1e5')
    call g%add('pier_friction', b%pier_friction, range='pier_friction >= 0 (finite)')
    call g%add('abutment_friction', b%abutment_friction, range='abutment_friction >= 0 (finite)')
    call g%add('fill_density_kg_m3', b%fill_density_kg_m3, unit='kg/m3', &
               range='0 <= fill_density_kg_m3 <= 1e5 (0: no fill)')
    call g%add('fill_level_m', b%fill_level_m, unit='m', range='0 <= fill_level_m <= 300 m', &
               about='real, m, the fill surface above the springings')
    call g%add('dispersion_angle_deg', b%dispersion_angle_deg, unit='deg', range='0 <= dispersion_angle_deg < 90', &
               about='real, deg from the vertical, either side of a live load')
    call g%add('dispersion', b%dispersion, choices=dispersion_names)
    call g%add('fill_friction_deg', b%fill_friction_deg, unit='deg', range='0 <= fill_friction_deg < 90', &
               about="real, deg, the fill's angle of friction (0: no horizontal pressure)")
    call g%add('passive_mobilisation', b%passive_mobilisation, range='0 <= passive_mobilisation <= 1', &
               about='real, the fraction of the passive pressure mobilised (0: active only)')
    call g%add('fill_model', b%fill_model, choices=fill_model_names)
    call g%add('fill_particle_size_m', b%fill_particle_size_m, unit='m', range='0 <= fill_particle_size_m <= 10 m', &
               about="real, m, the particles' size with fill_model = 'particles'")
    call g%add('fill_particle_friction', b%fill_particle_friction, range='fill_particle_friction >= 0 (finite)', &
               about="real, the particles' Coulomb coefficient with fill_model = 'particles'")
    call g%add('ring_compressive_strength_pa', b%ring_compressive_strength_pa, unit='Pa', &
               range='0 <= ring_compressive_strength_pa <= 1e10 Pa', &
               about="real, Pa, the ring's compressive strength for the limit analysis (0: rigid)")
    call g%add('pier_compressive_strength_pa', b%pier_compressive_strength_pa, unit='Pa', &
               range='0 <= pier_compressive_strength_pa <= 1e10 Pa', &
               about="real, Pa, the piers' compressive strength for the limit analysis (0: rigid)")
    call g%add('backing_compressive_strength_pa', b%backing_compressive_strength_pa, unit='Pa', &
               range='0 <= backing_compressive_strength_pa <= 1e10 Pa', &
               about="real, Pa, the backing's compressive strength for the limit analysis (0: rigid)")
    call g%add('backing_level_m', b%backing_level_m, unit='m', range='0 <= backing_level_m <= 300 m', &
               about='real, m, the top of the masonry backing above the springings (0: no backing)')
    call g%add('backing_course_m', b%backing_course_m, unit='m', range='0 <= backing_course_m <= 10 m', &
               about="real, m, the height of the backing's courses (0: "//fmt_significant(default_course_m, 3)//' m)')
    call g%add('backing_density_kg_m3', b%backing_density_kg_m3, unit='kg/m3', range='0 < backing_density_kg_m3 <= 1e5')
    call g%add('backing_friction', b%backing_friction, range='backing_friction >= 0 (finite)')
  end subroutine bridge_group

  !> Read and check the &bridge group of `path` (absent, or no span: no bridge).
  subroutine read_bridge_config(path, b, status)
    character(len=*), intent(in) :: path
    type(bridge_config_t), intent(out), target :: b
    type(status_t), intent(inout) :: status
    type(nml_group_t) :: g
    logical :: found
    integer :: k

    if (.not. status%ok) return
    call bridge_group(b, g)
    call g%read(path, status, found)
    if (.not. status%ok .or. .not. found) return
    b%n_spans = g%length('span_m', path, status)
    if (.not. status%ok) return
    if (b%n_spans == 0) then
      call fail(status, path//': &bridge gives no span: set span_m(1) > 0 [m] (and span_m(2), ... for more spans '// &
                'on piers)')
      return
    end if
    do k = 1, max_spans
      if (b%rise_m(k) /= b%rise_m(k) .or. b%span_m(k) /= b%span_m(k)) then
        call fail(status, path//': &bridge span_m('//itoa(k)//') or rise_m('//itoa(k)//') is not a finite number')
        return
      end if
    end do
    call g%check(path, status)
    if (.not. status%ok) return
    b%shape = lower(b%shape)
    b%fill_model = lower(b%fill_model)
    b%dispersion = lower(b%dispersion)
    do k = b%n_spans + 1, max_spans
      call need(b%rise_m(k) == 0.0_dp, path, 'bridge', 'rise_m('//itoa(k)//')', b%rise_m(k), &
                'none: there are '//itoa(b%n_spans)//' spans (span_m(1..'//itoa(b%n_spans)//'))', status)
    end do
    do k = 1, b%n_spans
      call check_span(b, k, path, status)
    end do
    if (.not. status%ok) return
    call check_rings(b, path, status)
    call check_supports(b, path, status)
    call check_fill(b, path, status)
    call check_backing(b, path, status)
    if (b%backing_level_m > 0.0_dp .and. b%backing_course_m == 0.0_dp) b%backing_course_m = default_course_m
  end subroutine read_bridge_config

  !> Backing stands on every haunch (its top above every springing's extrados end) and
  !> below every crown (a ring buried in it would be no arch); not under a fill of
  !> particles (not built).
  subroutine check_backing(b, path, status)
    type(bridge_config_t), intent(in) :: b
    character(len=*), intent(in) :: path
    type(status_t), intent(inout) :: status
    real(dp) :: back_m, up_m, spring_m, crown_m
    integer :: k
    if (.not. status%ok) return
    call need(b%pier_compressive_strength_pa == 0.0_dp .or. b%n_spans > 1, path, 'bridge', &
              'pier_compressive_strength_pa', b%pier_compressive_strength_pa, '0 with one span (no pier)', status)
    if (b%backing_level_m == 0.0_dp) then
      call need(b%backing_compressive_strength_pa == 0.0_dp, path, 'bridge', 'backing_compressive_strength_pa', &
                b%backing_compressive_strength_pa, '0 without backing (set backing_level_m > 0)', status)
      call need(b%backing_course_m == 0.0_dp, path, 'bridge', 'backing_course_m', b%backing_course_m, &
                '0 without backing (set backing_level_m > 0)', status)
      return
    end if
    spring_m = 0.0_dp
    crown_m = huge(1.0_dp)
    do k = 1, b%n_spans
      call springing_reach(bridge_intrados(b, k), b%ring_thickness_m, back_m, up_m)
      spring_m = max(spring_m, up_m)
      crown_m = min(crown_m, crown_top_m(b, k))
    end do
    call need(b%backing_level_m > spring_m, path, 'bridge', 'backing_level_m', b%backing_level_m, &
              'backing_level_m > '//fmt_significant(spring_m, 6)//" m, the extrados end of the highest springing "// &
              'joint: backing below it would stand on no haunch', status)
    call need(b%backing_level_m < crown_m, path, 'bridge', 'backing_level_m', b%backing_level_m, &
              'backing_level_m < '//fmt_significant(crown_m, 6)//" m, the lowest crown's extrados: a ring buried "// &
              'in its backing is no arch (model it as a wall, or lower the backing)', status)
    call need(b%fill_model == fill_model_columns, path, 'bridge', 'backing_level_m', b%backing_level_m, &
              "0 with fill_model = 'particles' (backing under a fill of particles is not built)", status)
  end subroutine check_backing

  !> A coefficient between rings only where there are two rings or more; left out, the
  !> ring's own.
  subroutine check_rings(b, path, status)
    type(bridge_config_t), intent(inout) :: b
    character(len=*), intent(in) :: path
    type(status_t), intent(inout) :: status
    if (.not. status%ok) return
    call need(b%n_rings >= 1 .and. b%n_rings <= max_rings, path, 'bridge', 'n_rings', b%n_rings, &
              '1 <= n_rings <= '//itoa(max_rings)//' (1: a single ring; a multi-ring brick arch is a few '// &
              'half-brick rings, each ring_thickness_m/n_rings deep)', status)
    if (.not. status%ok) return
    if (b%n_rings == 1) then
      call need(b%ring_joint_friction == unset_ring_joint_friction, path, 'bridge', 'ring_joint_friction', &
                b%ring_joint_friction, 'none with n_rings = 1: a single ring has no ring-to-ring joints (set '// &
                'n_rings >= 2 to split the ring)', status)
    else if (b%ring_joint_friction == unset_ring_joint_friction) then
      b%ring_joint_friction = b%ring_friction
    end if
  end subroutine check_rings

  !> A fill covers every ring (its surface not below any extrados); a dispersion angle
  !> or a fill level without a fill to spread or stand in is refused.
  subroutine check_fill(b, path, status)
    type(bridge_config_t), intent(in) :: b
    character(len=*), intent(in) :: path
    type(status_t), intent(inout) :: status
    real(dp) :: top_m
    integer :: k, highest
    if (.not. status%ok) return
    call need(b%passive_mobilisation == 0.0_dp .or. b%fill_friction_deg > 0.0_dp, path, 'bridge', &
              'passive_mobilisation', b%passive_mobilisation, '0 without fill_friction_deg > 0 (the passive '// &
              "pressure's coefficient follows from the fill's angle of friction)", status)
    call need(b%fill_model == fill_model_particles .or. b%fill_particle_size_m == 0.0_dp, path, 'bridge', &
              'fill_particle_size_m', b%fill_particle_size_m, "0 with fill_model = 'columns' (set "// &
              "fill_model = 'particles' to cut the fill into particles)", status)
    if (b%dispersion == dispersion_boussinesq) then
      call need(b%dispersion_angle_deg == 0.0_dp, path, 'bridge', 'dispersion_angle_deg', b%dispersion_angle_deg, &
                "0 with dispersion = 'boussinesq' (Flamant's stress spreads the load; the angle is the other "// &
                "rule, dispersion = 'angle')", status)
      call need(b%fill_density_kg_m3 > 0.0_dp, path, 'bridge', 'fill_density_kg_m3', b%fill_density_kg_m3, &
                "> 0 with dispersion = 'boussinesq' (a fill for the load to spread through, and fill_level_m its "// &
                'surface)', status)
      call need(b%fill_model == fill_model_columns, path, 'bridge', 'dispersion', b%dispersion, &
                "'angle' with fill_model = 'particles': the particles carry the load down by their contacts "// &
                "(dispersion = 'boussinesq' belongs to the columns' fill)", status)
      if (.not. status%ok) return
    end if
    if (b%fill_density_kg_m3 == 0.0_dp) then
      call need(b%fill_model == fill_model_columns, path, 'bridge', 'fill_density_kg_m3', b%fill_density_kg_m3, &
                "> 0 with fill_model = 'particles' (the particles' density; and fill_level_m their surface)", status)
      call need(b%fill_friction_deg == 0.0_dp, path, 'bridge', 'fill_friction_deg', b%fill_friction_deg, &
                '0 without a fill (set fill_density_kg_m3 > 0)', status)
      call need(b%dispersion_angle_deg == 0.0_dp, path, 'bridge', 'dispersion_angle_deg', b%dispersion_angle_deg, &
                '0 without a fill (set fill_density_kg_m3 > 0 and fill_level_m for the load to spread through)', &
                status)
      call need(b%fill_level_m == 0.0_dp, path, 'bridge', 'fill_level_m', b%fill_level_m, &
                '0 without a fill (set fill_density_kg_m3 > 0)', status)
      return
    end if
    highest = 1
    top_m = -huge(1.0_dp)
    do k = 1, b%n_spans
      if (crown_top_m(b, k) > top_m) then
        top_m = crown_top_m(b, k)
        highest = k
      end if
    end do
    call need(b%fill_level_m >= top_m, path, 'bridge', 'fill_level_m', b%fill_level_m, &
              'fill_level_m >= '//fmt_significant(top_m, 6)//' m, the extrados of span '//itoa(highest)// &
              "'s crown (its rise and ring_thickness_m): a fill surface below the extrados would cut the ring", status)
    if (b%dispersion == dispersion_boussinesq) &
      call need(b%fill_level_m > top_m, path, 'bridge', 'fill_level_m', b%fill_level_m, &
                'fill_level_m > '//fmt_significant(top_m, 6)//" m with dispersion = 'boussinesq': Flamant's stress "// &
                'at no depth is the load itself (span '//itoa(highest)//"'s crown would carry it undivided)", status)
    if (b%fill_model == fill_model_particles) call check_particles(b, top_m, path, status)
  end subroutine check_fill

  !> The fill as particles: a size, enough fill over the crown for a particle, not too many
  !> particles; none of the engineers' model's settings (the particles spread the load and
  !> press on the ring by their contacts).
  subroutine check_particles(b, top_m, path, status)
    type(bridge_config_t), intent(in) :: b
    real(dp), intent(in) :: top_m
    character(len=*), intent(in) :: path
    type(status_t), intent(inout) :: status
    real(dp) :: estimate
    call need(b%fill_particle_size_m > 0.0_dp, path, 'bridge', 'fill_particle_size_m', b%fill_particle_size_m, &
              "0 < fill_particle_size_m <= 10 m with fill_model = 'particles' (no size is assumed)", status)
    if (.not. status%ok) return
    call need(b%fill_level_m >= top_m + 0.5_dp*b%fill_particle_size_m, path, 'bridge', 'fill_level_m', &
              b%fill_level_m, 'fill_level_m >= '//fmt_significant(top_m + 0.5_dp*b%fill_particle_size_m, 6)// &
              ' m with particles: at least half a particle (fill_particle_size_m/2) over the crown, else the '// &
              'particles there would be slivers', status)
    estimate = bridge_length_m(b)*b%fill_level_m/b%fill_particle_size_m**2
    call need(estimate <= max_fill_particles, path, 'bridge', 'fill_particle_size_m', b%fill_particle_size_m, &
              'fill_particle_size_m >= '//fmt_significant(sqrt(bridge_length_m(b)*b%fill_level_m/max_fill_particles), 4)// &
              ' m: the fill would be cut into about '//itoa(nint(estimate))//' particles, more than '// &
              itoa(max_fill_particles), status)
    call need(b%dispersion_angle_deg == 0.0_dp, path, 'bridge', 'dispersion_angle_deg', b%dispersion_angle_deg, &
              "0 with fill_model = 'particles': the particles carry the load down (no dispersion rule)", status)
    call need(b%fill_friction_deg == 0.0_dp, path, 'bridge', 'fill_friction_deg', b%fill_friction_deg, &
              "0 with fill_model = 'particles': their pressure on the ring is their contacts' (their friction is "// &
              'fill_particle_friction)', status)
  end subroutine check_particles

  !> The height of span k's extrados at its crown above the springings [m].
  pure real(dp) function crown_top_m(b, k)
    type(bridge_config_t), intent(in) :: b
    integer, intent(in) :: k
    type(intrados_t) :: c
    c = bridge_intrados(b, k)
    crown_top_m = c%rise_m + b%ring_thickness_m
    if (b%shape == shape_pointed) crown_top_m = crown_extrados_m(c, b%ring_thickness_m)
  end function crown_top_m

  !> Span k's rise against its shape, its ring against its span, its voussoirs' lengths.
  subroutine check_span(b, k, path, status)
    type(bridge_config_t), intent(inout) :: b
    integer, intent(in) :: k
    character(len=*), intent(in) :: path
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: rise, half
    real(dp) :: span

    if (.not. status%ok) return
    span = b%span_m(k)
    rise = 'rise_m('//itoa(k)//')'
    half = fmt_significant(0.5_dp*span, 6)
    select case (b%shape)
    case (shape_semicircular)
      ! The rise of a semicircle is its radius: left out, or given equal to it.
      if (b%rise_m(k) == 0.0_dp) b%rise_m(k) = 0.5_dp*span
      call need(abs(b%rise_m(k) - 0.5_dp*span) <= 1.0e-9_dp*span, path, 'bridge', rise, b%rise_m(k), &
                rise//' = span_m/2 = '//half//' m for a semicircular arch (or leave it out); another rise is '// &
                "'segmental' (below half the span), 'elliptical' or 'pointed' (above)", status)
    case (shape_segmental)
      call need_rise(b%rise_m(k) > 0.0_dp .and. b%rise_m(k) <= 0.5_dp*span, '0 < '//rise//' <= span_m/2 = '// &
                     half//" m for a segmental arch (a circular arc no more than a semicircle; above half the span "// &
                     "choose 'pointed' or 'elliptical')")
    case (shape_pointed)
      call need_rise(b%rise_m(k) >= 0.5_dp*span, rise//' >= span_m/2 = '//half//' m for a pointed arch (two arcs '// &
                     "centred on the springing line meet above a semicircle; below choose 'segmental')")
      call need(modulo(b%n_voussoirs, 2) == 0, path, 'bridge', 'n_voussoirs', b%n_voussoirs, &
                'an even n_voussoirs for a pointed arch: its two arcs meet at the apex at an angle, where a '// &
                'joint must stand (a keystone across it would not be convex)', status)
    case (shape_three_centred)
      call need_rise(b%rise_m(k) > three_centred_min_rise_ratio*span .and. b%rise_m(k) < 0.5_dp*span, &
                     fmt_significant(three_centred_min_rise_ratio*span, 6)//' m < '//rise//' < span_m/2 = '//half// &
                     ' m for a three-centred arch of 60-degree haunches (lower, its haunch radius would vanish; '// &
                     "at half the span it is a semicircle)")
    case (shape_elliptical, shape_parabolic)
      call need_rise(b%rise_m(k) > 0.0_dp, '0 < '//rise//' <= 200 m (give the rise of span '//itoa(k)//')')
    end select
    if (.not. status%ok) return
    call need(b%ring_thickness_m <= max_ring_over_span*span, path, 'bridge', 'ring_thickness_m', b%ring_thickness_m, &
              '0 < ring_thickness_m <= span_m('//itoa(k)//')/4 = '//fmt_significant(max_ring_over_span*span, 6)// &
              ' m: a ring deeper than a quarter of its span is a wall pierced by an opening, not an arch ring', status)
    ! No slivers follow: with the ring at most a quarter of the span and at most 200
    ! voussoirs, each is at least ring_thickness_m/50 long (the &arch builder's rule asks
    ! for a hundredth).

  contains

    subroutine need_rise(good, allowed)
      logical, intent(in) :: good
      character(len=*), intent(in) :: allowed
      call need(good, path, 'bridge', rise, b%rise_m(k), allowed, status)
    end subroutine need_rise

  end subroutine check_span

  !> The skewbacks carry their arches: each abutment reaches back beyond its springing
  !> joint's extrados end; the spans meet their piers side by side: a pier is wide enough
  !> for the springing joints of both spans it carries.
  subroutine check_supports(b, path, status)
    type(bridge_config_t), intent(in) :: b
    character(len=*), intent(in) :: path
    type(status_t), intent(inout) :: status
    real(dp) :: back(max_spans), up
    integer :: k
    do k = 1, b%n_spans
      call springing_reach(bridge_intrados(b, k), b%ring_thickness_m, back(k), up)
    end do
    do k = 1, b%n_spans, max(1, b%n_spans - 1)   ! the first span's left end and the last span's right end
      call need(b%abutment_width_m > back(k), path, 'bridge', 'abutment_width_m', b%abutment_width_m, &
                'abutment_width_m > '//fmt_significant(back(k), 6)//' m, the horizontal reach of span '//itoa(k)// &
                "'s springing joint (ring_thickness_m across the intrados there): a narrower skewback would not "// &
                'carry the extrados end of its arch', status)
    end do
    do k = 1, b%n_spans - 1
      call need(b%pier_width_m >= back(k) + back(k + 1), path, 'bridge', 'pier_width_m', b%pier_width_m, &
                'pier_width_m >= '//fmt_significant(back(k) + back(k + 1), 6)//' m: spans '//itoa(k)//' and '// &
                itoa(k + 1)//' do not meet pier '//itoa(k)//' side by side (their springing joints reach '// &
                fmt_significant(back(k), 6)//' and '//fmt_significant(back(k + 1), 6)//' m over it, and would '// &
                'overlap)', status)
    end do
  end subroutine check_supports

  !> The intrados of span k.
  pure function bridge_intrados(b, k) result(c)
    type(bridge_config_t), intent(in) :: b
    integer, intent(in) :: k
    type(intrados_t) :: c
    c = intrados_init(b%shape, b%span_m(k), b%rise_m(k))
  end function bridge_intrados

  !> From the back of the left abutment to the back of the right one [m].
  pure real(dp) function bridge_length_m(b)
    type(bridge_config_t), intent(in) :: b
    bridge_length_m = sum(b%span_m(1:b%n_spans)) + (b%n_spans - 1)*b%pier_width_m + 2.0_dp*b%abutment_width_m
  end function bridge_length_m

end module voussoir_bridge_config
