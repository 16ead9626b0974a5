!> The linear-programming limit analysis that voussoir-limit makes of any assembly
!> (voussoir_limit_lp): the interfaces, both capacities (associative and
!> non-associative) and, for an arch, the joint and side of every interface; with a
!> &load, its point and distributed loads, and along its path the critical position of
!> the live loads (the least load factor) with the curve of load factor against position.
!> docs/limit_analysis.md, "Any assembly" and "Loads".
module voussoir_limit_lp_study
  use voussoir_kinds, only: dp, g_m_s2
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa, fmt_significant
  use voussoir_load_config, only: load_config_t
  use voussoir_placed_loads, only: placed_loads_t, place_loads, moves_on_top, vehicle_x, top_surface, fill_column, &
    boussinesq_cutoff
  use voussoir_assembly, only: assembly_t, between_rings
  use voussoir_hinge_side, only: side_intrados, side_extrados
  use voussoir_block_interfaces, only: interface_set_t, find_interfaces
  use voussoir_limit_lp, only: block_loads_t, lp_result_t, block_loads, add_placed_loads, lp_outcome_unbounded
  use voussoir_limit_crushing, only: crushing_t, crushing_capacity, crushing_nonassociative
  implicit none
  private

  public :: lp_study_t, lp_direction_t, lp_study, path_position_m

  character(len=*), parameter :: live_acceleration_words = &
    'horizontal acceleration lambda g towards +x (lambda x the weight of each block)'

  !> Both capacities of the live load reversed: the horizontal acceleration lambda g
  !> towards -x (the loads in place, the live one turned round).
  type :: lp_direction_t
    logical :: applies = .false.              !! the live load is the horizontal acceleration
    logical :: solved = .false.               !! the associative LP has a solution
    logical :: nonassociative_solved = .false.
    character(len=:), allocatable :: note     !! why not, when not solved
    type(lp_result_t) :: assoc, nonassoc
    integer :: steps = 0                      !! steps of the non-associative iteration
    logical :: converged = .false.
    integer :: crushing_steps = 0             !! LPs of the crushing iteration (associative)
    logical :: crushing_converged = .true.
    logical :: crushed_through = .false.      !! an interface crushed through (its ends met)
  end type lp_direction_t

  !> Both capacities of an assembly under the horizontal acceleration lambda g towards +x
  !> (or lambda x the live point loads of &load); `neg`, towards -x.
  type :: lp_study_t
    logical :: solved = .false.               !! the associative LP has a solution
    logical :: nonassociative_solved = .false.
    character(len=:), allocatable :: note     !! why not, when not solved
    character(len=:), allocatable :: assembly !! 'arch', 'wall' or 'polygon file'
    type(interface_set_t) :: faces
    type(lp_result_t) :: assoc, nonassoc
    integer :: steps = 0                      !! steps of the non-associative iteration
    logical :: converged = .false.
    integer, allocatable :: joint(:)          !! arch joint 0..n of each interface, -1 if none
    integer, allocatable :: end_side(:, :)    !! (2, n_interfaces) side_intrados / side_extrados of each end (arches)
    character(len=:), allocatable :: live_load !! the live load in words
    logical :: live_is_acceleration = .true.  !! the live load is lambda g towards +x (else point loads)
    type(placed_loads_t) :: placed            !! the loads of &load (at the critical position on a path)
    logical :: has_path = .false.             !! the live loads moved along &load's path
    real(dp) :: critical_x_m = 0.0_dp         !! the position of least load factor (the vehicle's: its live loads' resultant) [m]
    real(dp) :: critical_load_factor = 0.0_dp !! the associative load factor there
    real(dp), allocatable :: curve_x_m(:)     !! the positions on the path [m]
    real(dp), allocatable :: curve_load_factor(:) !! the associative load factor at each (-1: unbounded)
    logical, allocatable :: curve_at_joint(:) !! the position puts a live load over a joint's end (not a grid point)
    character(len=32), allocatable :: block_name(:) !! the assembly's names of its blocks, where it has them
    type(lp_direction_t) :: neg               !! the horizontal acceleration towards -x
    type(crushing_t) :: crush                 !! the compressive strength (rigid: 0)
    integer :: crushing_steps = 0             !! LPs of the crushing iteration (associative, +x)
    logical :: crushing_converged = .true.
    logical :: crushed_through = .false.      !! an interface crushed through (its ends met)
  end type lp_study_t

contains

  !> The LP analysis of `asm` with Coulomb friction `friction` at every interface, the
  !> weights of density x area x width x g, the loads of `load` (if given), and the
  !> interface ends set in by `inset_m`. A refusal (no interfaces,
  !> infeasible, unbounded) comes back in `status`. Where the live load is the horizontal
  !> acceleration, the same towards -x in `study%neg` (its refusal in `study%neg%note`).
  !> With `compressive_strength_pa` > 0, the interfaces crush (voussoir_limit_crushing).
  subroutine lp_study(asm, density_kg_m3, width_m, friction, inset_m, study, status, load, joint_friction, &
                      compressive_strength_pa, loads_dead, fill_as_mass)
    type(assembly_t), intent(in) :: asm
    real(dp), intent(in) :: density_kg_m3, width_m, friction, inset_m
    type(lp_study_t), intent(out) :: study
    type(status_t), intent(inout) :: status
    type(load_config_t), intent(in), optional :: load
    real(dp), intent(in), optional :: joint_friction(0:) !! arch joint j's coefficient where >= 0 (else `friction`)
    real(dp), intent(in), optional :: compressive_strength_pa !! sigma_c [Pa]; absent or 0: rigid
    !> Every load of `load` dead, where a run applies it (no path), the live load the
    !> horizontal acceleration: the static capacity of a shaken, loaded assembly.
    logical, intent(in), optional :: loads_dead
    !> A fill as voussoir-run has it (docs/bridges.md, "Fill in the dynamics"): mass its
    !> blocks carry, so the horizontal acceleration moves it too, and its horizontal
    !> pressure at the active bound alone (a constant force in the run)
    logical, intent(in), optional :: fill_as_mass
    type(block_loads_t) :: loads
    real(dp), allocatable :: mu(:)
    real(dp) :: size_m, shift_m
    integer :: b
    logical :: all_dead

    study%crush = crushing_t(0.0_dp, width_m)
    if (present(compressive_strength_pa)) study%crush%strength_pa = compressive_strength_pa
    size_m = 0.0_dp
    do b = 1, asm%n_bodies
      size_m = max(size_m, maxval(maxval(asm%polygon(b)%xy, dim=2) - minval(asm%polygon(b)%xy, dim=2)))
    end do
    ! Faces on one line to 1e-6 of the largest block (round-off of polygon files).
    call find_interfaces(asm, 1.0e-6_dp*size_m, inset_m, study%faces, status)
    if (.not. status%ok) return
    do b = 1, asm%n_bodies
      if (asm%driven(b) .or. any(study%faces%body == b)) cycle
      call fail(status, 'block '//itoa(b)//' touches no other block: nothing holds it up')
      return
    end do
    call part_crushing(asm, study, status)
    if (.not. status%ok) return
    call name_arch_joints(asm, study)
    if (allocated(asm%block_name)) study%block_name = asm%block_name
    mu = interface_friction(asm, study%faces, friction)
    if (present(joint_friction)) then
      call joint_coefficients(asm, study, joint_friction, mu, status)
      if (.not. status%ok) return
    end if
    shift_m = 0.0_dp
    study%live_load = live_acceleration_words
    allocate (study%placed%block(0), study%placed%source(0), study%placed%xy(2, 0), study%placed%force_n(2, 0), &
              study%placed%live(0), study%placed%kind(0), study%placed%surface_source(0), &
              study%placed%surface_xy(2, 0), study%placed%surface_force_n(2, 0), study%placed%surface_spread_x_m(2, 0), &
              study%placed%surface_patch_m(0))
    all_dead = .false.
    if (present(loads_dead)) all_dead = loads_dead
    if (present(load) .and. all_dead) then
      call place_loads(load, asm, 0.0_dp, study%placed, status)
      if (.not. status%ok) return
      study%placed%live = .false.
      study%live_load = study%live_load//'; dead: the weights and every load of &load, where a run applies it'
    else if (present(load)) then
      if (load%path_points >= 2) then
        call critical_position(asm, density_kg_m3, width_m, load, study, mu, shift_m, status)
        if (.not. status%ok) return
      end if
      call place_loads(load, asm, shift_m, study%placed, status)
      if (.not. status%ok) return
      study%live_load = live_load_words(load)
      ! With a fill the live loads stand on its surface, not on the blocks' top.
      if (asm%has_fill .and. index(study%live_load, ', on the top surface') > 0) &
        study%live_load = replaced(study%live_load, ', on the top surface', ', on the fill''s surface')
      if (asm%has_fill) study%live_load = study%live_load//'; and the fill: its weight on the blocks beneath its '// &
        'surface at y = '//fmt_significant(asm%fill_level_m, 6)//' m, the live loads standing on that surface and '// &
        trim(spread_words(asm))
      if (asm%fill_passive_k > 0.0_dp) study%live_load = study%live_load//'; its horizontal pressure on the '// &
        'ring between '//fmt_significant(asm%fill_active_k, 4)//' and '//fmt_significant(asm%fill_passive_k, 4)// &
        ' x the vertical stress (active; passive as mobilised), the LP choosing'
      study%live_is_acceleration = .not. any(study%placed%live)
    end if
    call block_loads(asm, density_kg_m3, width_m, g_m_s2, loads)
    call add_placed_loads(study%placed, loads)
    if (present(fill_as_mass)) then
      if (fill_as_mass .and. asm%has_fill .and. study%live_is_acceleration) call carry_fill(asm, loads)
    end if
    call crushing_capacity(asm, study%faces, loads, mu, study%crush, study%assoc, study%crushing_steps, &
                           study%crushing_converged, study%crushed_through, status)
    if (.not. status%ok) return
    study%solved = .true.
    call crushing_nonassociative(asm, study%faces, loads, mu, study%crush, study%assoc, study%nonassoc, study%steps, &
                                 study%converged, status)
    study%nonassociative_solved = status%ok
    if (study%live_is_acceleration) call reversed_direction(asm, study%faces, loads, mu, study%crush, study%neg)
    if (.not. study%live_is_acceleration) study%neg%note = 'the live load is the point loads of &load: '// &
      'the -x direction is that of the horizontal acceleration only'
  end subroutine lp_study

  !> How the live loads spread through the fill of `asm`, in words.
  function spread_words(asm) result(text)
    type(assembly_t), intent(in) :: asm
    character(len=:), allocatable :: text
    if (asm%dispersion_boussinesq) then
      text = 'spread through it by Boussinesq (Flamant''s vertical stress on the blocks'' top, truncated where '// &
             'it falls below '//fmt_significant(boussinesq_cutoff, 3)//' x the stress beneath the load, scaled to '// &
             'the load)'
    else
      text = 'spread through it at '//fmt_significant(asm%dispersion_angle_deg, 6)//' deg from the vertical either side'
    end if
  end function spread_words

  !> Both capacities with the live load turned round (the dead loads as they are); a
  !> refusal (a block held against -x) is the direction's note, not an error.
  subroutine reversed_direction(asm, faces, loads, mu, crush, neg)
    type(assembly_t), intent(in) :: asm
    type(interface_set_t), intent(in) :: faces
    type(block_loads_t), intent(in) :: loads
    real(dp), intent(in) :: mu(:)
    type(crushing_t), intent(in) :: crush
    type(lp_direction_t), intent(inout) :: neg
    type(block_loads_t) :: reversed
    type(status_t) :: status
    reversed = loads
    reversed%live_n = -loads%live_n
    reversed%live_moment_nm = -loads%live_moment_nm
    neg%applies = .true.
    call crushing_capacity(asm, faces, reversed, mu, crush, neg%assoc, neg%crushing_steps, neg%crushing_converged, &
                           neg%crushed_through, status)
    if (.not. status%ok) then
      neg%note = trim(status%message)
      return
    end if
    neg%solved = .true.
    call crushing_nonassociative(asm, faces, reversed, mu, crush, neg%assoc, neg%nonassoc, neg%steps, neg%converged, &
                                 status)
    neg%nonassociative_solved = status%ok
  end subroutine reversed_direction

  !> The Coulomb coefficient of each interface of `faces`: `friction`, or for a bridge's
  !> parts the lesser of its two blocks', or between two rings of a multi-ring bridge the
  !> coefficient of the joints between rings.
  pure function interface_friction(asm, faces, friction) result(mu)
    type(assembly_t), intent(in) :: asm
    type(interface_set_t), intent(in) :: faces
    real(dp), intent(in) :: friction
    real(dp) :: mu(faces%n)
    integer :: k
    mu = friction
    do k = 1, faces%n
      if (allocated(asm%friction)) mu(k) = minval(asm%friction(faces%body(:, k)))
      if (allocated(asm%ring)) then
        if (between_rings(asm%ring, faces%body(1, k), faces%body(2, k))) mu(k) = asm%ring_joint_friction
      end if
    end do
  end function interface_friction

  !> The friction of each interface that is arch joint j where `joint_friction(j) >= 0`,
  !> as the dynamics takes it (voussoir_contact_law); the others keep theirs.
  subroutine joint_coefficients(asm, study, joint_friction, mu, status)
    type(assembly_t), intent(in) :: asm
    type(lp_study_t), intent(in) :: study
    real(dp), intent(in) :: joint_friction(0:)
    real(dp), intent(inout) :: mu(:)
    type(status_t), intent(inout) :: status
    integer :: k, j
    if (all(joint_friction < 0.0_dp)) return
    if (.not. allocated(asm%joint_bodies)) then
      call fail(status, 'joint_friction is set, but the assembly has no numbered joints')
      return
    end if
    do j = ubound(asm%joint_bodies, 2) + 1, ubound(joint_friction, 1)
      if (joint_friction(j) < 0.0_dp) cycle
      call fail(status, 'joint_friction('//itoa(j)//') is set: the arch has joints 0..'// &
                itoa(ubound(asm%joint_bodies, 2))//' only')
      return
    end do
    do k = 1, study%faces%n
      j = study%joint(k)
      if (j < 0) cycle
      if (joint_friction(j) >= 0.0_dp) mu(k) = joint_friction(j)
    end do
  end subroutine joint_coefficients

  !> Position i of `path_points` on the path from x0 to x1 [m].
  pure real(dp) function path_position_m(load, i)
    type(load_config_t), intent(in) :: load
    integer, intent(in) :: i
    ! Weighted this way, a path symmetric about x = 0 has its middle position at 0 exactly.
    path_position_m = ((load%path_points - i)*load%path_x0_m + (i - 1)*load%path_x1_m)/(load%path_points - 1)
  end function path_position_m

  !> The associative load factor with the vehicle (the resultant of the live loads) at each
  !> position of the path (every live load keeping its offset from it, on the top surface),
  !> and at every position in the path's range where a live load (any axle) stands exactly
  !> over a joint's end on the top surface: the load factor jumps there (a load on a joint's
  !> corner against one on a block), so a grid alone can miss the least. The least one (the
  !> first of equal ones, to 1e-9) is the critical position, `shift_m` the shift of the live
  !> loads that puts them there. A position where no mechanism opens (the loads on a
  !> support) has no load factor.
  subroutine critical_position(asm, density_kg_m3, width_m, load, study, mu, shift_m, status)
    type(assembly_t), intent(in) :: asm
    real(dp), intent(in) :: density_kg_m3, width_m
    type(load_config_t), intent(in) :: load
    type(lp_study_t), intent(inout) :: study
    real(dp), intent(in) :: mu(:)
    real(dp), intent(out) :: shift_m
    type(status_t), intent(inout) :: status
    real(dp), allocatable :: joints_x(:)
    real(dp) :: lowest
    integer :: i, best

    study%has_path = .true.
    call joint_positions(asm, study%faces, load, joints_x)
    study%curve_x_m = [(path_position_m(load, i), i=1, load%path_points)]
    study%curve_at_joint = [(.false., i=1, load%path_points)]
    do i = 1, size(joints_x)
      if (any(abs(study%curve_x_m - joints_x(i)) <= 1.0e-9_dp)) cycle
      study%curve_x_m = [study%curve_x_m, joints_x(i)]
      study%curve_at_joint = [study%curve_at_joint, .true.]
    end do
    call sort_curve(study%curve_x_m, study%curve_at_joint)
    allocate (study%curve_load_factor(size(study%curve_x_m)))
    best = 0
    do i = 1, size(study%curve_x_m)
      call load_factor_at(asm, density_kg_m3, width_m, load, study, mu, study%curve_x_m(i), &
                          study%curve_load_factor(i), status)
      if (.not. status%ok) return
      if (study%curve_load_factor(i) >= 0.0_dp) best = i
    end do
    if (best == 0) then
      call fail(status, 'no position of &load path_x0_m .. path_x1_m has a load factor: the live loads open no '// &
                'mechanism anywhere along the path')
      return
    end if
    ! The first position within 1e-9 of the least (a symmetric assembly has two, equal
    ! but for round-off: the choice must not depend on it).
    lowest = minval(study%curve_load_factor, mask=study%curve_load_factor >= 0.0_dp)
    best = findloc(study%curve_load_factor >= 0.0_dp .and. study%curve_load_factor <= lowest*(1 + 1.0e-9_dp), &
                   .true., dim=1)
    study%critical_x_m = study%curve_x_m(best)
    study%critical_load_factor = study%curve_load_factor(best)
    shift_m = study%critical_x_m - vehicle_x(load)
  end subroutine critical_position

  !> The associative load factor with the vehicle at `x_m` (-1 where no mechanism opens).
  subroutine load_factor_at(asm, density_kg_m3, width_m, load, study, mu, x_m, load_factor, status)
    type(assembly_t), intent(in) :: asm
    real(dp), intent(in) :: density_kg_m3, width_m, mu(:), x_m
    type(load_config_t), intent(in) :: load
    type(lp_study_t), intent(in) :: study
    real(dp), intent(out) :: load_factor
    type(status_t), intent(inout) :: status
    type(placed_loads_t) :: placed
    type(block_loads_t) :: loads
    type(lp_result_t) :: res
    type(status_t) :: lp_status
    integer :: steps
    logical :: converged, crushed
    load_factor = -1.0_dp
    call place_loads(load, asm, x_m - vehicle_x(load), placed, status)
    if (.not. status%ok) return
    call block_loads(asm, density_kg_m3, width_m, g_m_s2, loads)
    call add_placed_loads(placed, loads)
    lp_status = status_t()
    call crushing_capacity(asm, study%faces, loads, mu, study%crush, res, steps, converged, crushed, lp_status)
    if (lp_status%ok) then
      load_factor = res%load_factor
    else if (res%outcome /= lp_outcome_unbounded) then
      status = lp_status
      status%message = trim(status%message)//' (live loads at path position x = '//fmt_significant(x_m, 6)//' m)'
    end if
  end subroutine load_factor_at

  !> The vehicle's positions in the path's range [m] at which one of its live loads (any
  !> axle) stands over the end of an interface on the top surface of `asm` (on a ring, the
  !> extrados ends of its joints), a micrometre to either side of it.
  pure subroutine joint_positions(asm, faces, load, x)
    type(assembly_t), intent(in) :: asm
    type(interface_set_t), intent(in) :: faces
    type(load_config_t), intent(in) :: load
    real(dp), allocatable, intent(out) :: x(:)
    real(dp), parameter :: joint_side_m = 1.0e-6_dp
    real(dp) :: p(2), y, offset, xv
    integer :: k, e, j, a, blk, side
    logical :: ok
    allocate (x(0))
    do k = 1, faces%n
      do e = 1, 2
        p = faces%end_xy(:, e, k)
        call top_surface(asm, p(1), y, blk, ok)
        if (.not. ok .or. abs(y - p(2)) > 1.0e-9_dp*max(1.0_dp, abs(p(2)))) cycle
        do j = 1, load%n_point_loads
          if (.not. load%point_load_live(j)) cycle
          do a = 0, load%n_axles
            offset = load%point_load_x_m(j) - vehicle_x(load)
            if (a > 0) offset = offset + load%axle_spacing_m(a)
            ! A micrometre either side: the load on each of the two blocks that meet there.
            do side = -1, 1, 2
              xv = p(1) - offset + side*joint_side_m
              if (xv < load%path_x0_m .or. xv > load%path_x1_m) cycle
              if (any(abs(x - xv) <= 1.0e-9_dp)) cycle
              x = [x, xv]
            end do
          end do
        end do
      end do
    end do
  end subroutine joint_positions

  !> Sort the positions `x` ascending, `tag` with them (insertion sort: tens of entries).
  pure subroutine sort_curve(x, tag)
    real(dp), intent(inout) :: x(:)
    logical, intent(inout) :: tag(:)
    real(dp) :: xk
    logical :: tk
    integer :: i, k
    do k = 2, size(x)
      xk = x(k)
      tk = tag(k)
      i = k - 1
      do while (i >= 1)
        if (x(i) <= xk) exit
        x(i + 1) = x(i)
        tag(i + 1) = tag(i)
        i = i - 1
      end do
      x(i + 1) = xk
      tag(i + 1) = tk
    end do
  end subroutine sort_curve

  !> `text` with its first `old` replaced by `new`.
  pure function replaced(text, old, new) result(out)
    character(len=*), intent(in) :: text, old, new
    character(len=:), allocatable :: out
    integer :: k
    k = index(text, old)
    out = text
    if (k > 0) out = text(:k - 1)//new//text(k + len(old):)
  end function replaced

  !> 'live point loads of &load: 1 of 1e4 N (x 3 axles) ...; dead: ...'
  function live_load_words(load) result(text)
    type(load_config_t), intent(in) :: load
    character(len=:), allocatable :: text
    integer :: j, n_live, n_dead
    n_live = count(load%point_load_live(1:load%n_point_loads))
    n_dead = load%n_point_loads - n_live
    if (n_live == 0) then
      text = 'horizontal acceleration lambda g towards +x (lambda x the weight of each block)'
    else
      text = 'lambda x the live point loads of &load ('
      do j = 1, load%n_point_loads
        if (.not. load%point_load_live(j)) cycle
        if (text(len(text):) /= '(') text = text//', '
        text = text//'load '//itoa(j)//': '//fmt_significant(load%point_load_n(j), 6)//' N at '// &
               fmt_significant(load%point_load_dir_deg(j), 6)//' deg'
        if (load%point_load_patch_m(j) > 0.0_dp) text = text//' spread over a patch of '// &
          fmt_significant(load%point_load_patch_m(j), 6)//' m'
      end do
      text = text//')'
      if (load%n_axles > 0) text = text//', each repeated at '//itoa(load%n_axles)//' axle offsets'
      if (moves_on_top(load)) text = text//', on the top surface'
      if (load%path_points >= 2) text = text//' at the critical position'
    end if
    text = text//'; dead: the weights'
    if (n_dead > 0) text = text//' and '//itoa(n_dead)//' dead point load'//trim(merge('s', ' ', n_dead > 1))
    if (load%dead_load_n_per_m > 0.0_dp) text = text//' and '//fmt_significant(load%dead_load_n_per_m, 6)// &
      ' N/m from x = '//fmt_significant(load%dead_load_x0_m, 6)//' to '//fmt_significant(load%dead_load_x1_m, 6)//' m'
  end function live_load_words

  !> For an arch, the joint j (0..n) of each interface (the one between the same two
  !> bodies) and which of its ends is on the intrados.
  pure subroutine name_arch_joints(asm, study)
    type(assembly_t), intent(in) :: asm
    type(lp_study_t), intent(inout) :: study
    integer :: k, j, e
    real(dp) :: d_in, d_ext
    allocate (study%joint(study%faces%n), study%end_side(2, study%faces%n))
    study%joint = -1
    study%end_side = 0
    if (.not. allocated(asm%joint_bodies)) return
    do k = 1, study%faces%n
      do j = lbound(asm%joint_bodies, 2), ubound(asm%joint_bodies, 2)
        if (all(asm%joint_bodies(:, j) == study%faces%body(:, k)) .or. &
            all(asm%joint_bodies(:, j) == study%faces%body(2:1:-1, k))) study%joint(k) = j
      end do
      j = study%joint(k)
      if (j < 0) cycle
      do e = 1, 2
        d_in = norm2(study%faces%end_xy(:, e, k) - asm%joint_intrados_xy(:, j))
        d_ext = norm2(study%faces%end_xy(:, e, k) - asm%joint_extrados_xy(:, j))
        study%end_side(e, k) = merge(side_intrados, side_extrados, d_in < d_ext)
      end do
    end do
  end subroutine name_arch_joints

  !> The fill of `asm` as mass its free blocks carry under the horizontal acceleration:
  !> each block's column (fill_column, the same trapezoids whose weight place_loads puts
  !> on it) loaded by lambda times its weight towards +x at the column's centroid, as the
  !> run's composite body takes it; its horizontal pressure fixed at the active bound.
  pure subroutine carry_fill(asm, loads)
    type(assembly_t), intent(in) :: asm
    type(block_loads_t), intent(inout) :: loads
    real(dp) :: area_m2, centroid_xy(2), polar_m4, force_n
    integer :: b
    do b = 1, asm%n_bodies
      if (asm%driven(b)) cycle
      call fill_column(asm, b, area_m2, centroid_xy, polar_m4)
      if (.not. area_m2 > 0.0_dp) cycle
      force_n = asm%fill_weight_n_m2*area_m2
      loads%live_n(1, b) = loads%live_n(1, b) + force_n
      ! The moment of [force_n, 0] at the column's centroid about the block's.
      loads%live_moment_nm(b) = loads%live_moment_nm(b) - (centroid_xy(2) - loads%centroid(2, b))*force_n
    end do
    if (loads%n_bounded > 0) loads%bounded_hi_n = loads%bounded_lo_n
  end subroutine carry_fill

  !> A bridge's parts' compressive strengths on the study's interfaces (study%crush), or a
  !> refusal beside &limit compressive_strength_pa (one strength for every interface).
  subroutine part_crushing(asm, study, status)
    type(assembly_t), intent(in) :: asm
    type(lp_study_t), intent(inout) :: study
    type(status_t), intent(inout) :: status
    if (.not. allocated(asm%compressive_strength_pa)) return
    if (.not. any(asm%compressive_strength_pa > 0.0_dp)) return
    if (study%crush%strength_pa > 0.0_dp) then
      call fail(status, '&limit compressive_strength_pa gives every interface one strength, and &bridge gives '// &
                'its parts their own: give one or the other')
      return
    end if
    study%crush%face_strength_pa = face_strengths(asm, study%faces)
  end subroutine part_crushing

  !> Each interface's compressive strength [Pa] from its two blocks' (0: rigid): the lesser
  !> of two that crush, the one that does beside a rigid block, 0 between rigid blocks.
  pure function face_strengths(asm, faces) result(strength)
    type(assembly_t), intent(in) :: asm
    type(interface_set_t), intent(in) :: faces
    real(dp) :: strength(faces%n), a, b
    integer :: k
    do k = 1, faces%n
      a = asm%compressive_strength_pa(faces%body(1, k))
      b = asm%compressive_strength_pa(faces%body(2, k))
      strength(k) = max(a, b)
      if (a > 0.0_dp .and. b > 0.0_dp) strength(k) = min(a, b)
    end do
  end function face_strengths

end module voussoir_limit_lp_study
