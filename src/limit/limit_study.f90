!> The limit analysis a voussoir-limit input asks for: the optional &limit group
!> (docs/limit_analysis.md) and the analyses of the assembly it describes: for the arch
!> builder the four-hinge analysis, the minimum thickness and the LP; for a &wall or a
!> polygon file the LP alone.
module voussoir_limit_study
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_config, only: config_t, springings_none, has_loads
  use voussoir_load_config, only: load_config_t
  use voussoir_vehicle_config, only: vehicle_config_t
  use voussoir_placed_loads, only: placed_loads_t, place_loads, vehicle_x
  use voussoir_limit_lp_study, only: path_position_m
  use voussoir_namelist_group, only: nml_group_t
  use voussoir_input_range, only: need, need_range
  use voussoir_text, only: itoa, fmt_significant
  use voussoir_assembly, only: assembly_t
  use voussoir_config_assembly, only: build_config_assembly
  use voussoir_limit_lp_study, only: lp_study_t, lp_study
  use voussoir_limit_analysis, only: limit_result_t, horizontal_capacity
  use voussoir_minimum_thickness, only: thickness_search => minimum_thickness
  use voussoir_load_case_config, only: case_load
  use voussoir_limit_load_cases, only: case_study_t, factored_assembly, governing_case, live_total_n
  implicit none
  private

  public :: limit_options_t, thickness_result_t, read_limit_group, analyse, limit_table

  real(dp), parameter :: unset = -huge(1.0_dp)  !! inset_m, compressive_strength_pa not given

  !> The exhaustive four-hinge search costs n^4: 0.5 s at 100 voussoirs, 9 s at 200,
  !> 40 s at 300 (docs/limit_analysis.md); beyond 200 the answer hardly moves.
  integer, parameter :: max_limit_voussoirs = 200

  !> The &limit group.
  type :: limit_options_t
    logical :: minimum_thickness = .true.  !! compute the minimum thickness
    real(dp) :: inset_m = 0.0_dp           !! pivot inset of the analysis [m]
    real(dp) :: compressive_strength_pa = 0.0_dp !! sigma_c of the LP's interfaces [Pa]; 0: rigid (infinite)
  end type limit_options_t

  !> The minimum thickness of the arch's shape (embrace, voussoirs, r_ext, inset).
  type :: thickness_result_t
    logical :: computed = .false.
    real(dp) :: ratio_ext = 0.0_dp, ratio_mean = 0.0_dp
    integer, allocatable :: hinges(:), sides(:)
  end type thickness_result_t

contains

  !> The &limit table over `opts`, set to the defaults: inset_m and compressive_strength_pa
  !> unset (read_limit_group resolves them).
  subroutine limit_table(opts, g)
    type(limit_options_t), intent(inout), target :: opts
    type(nml_group_t), intent(out) :: g
    opts%inset_m = unset
    opts%compressive_strength_pa = unset
    g%name = 'limit'
    call g%add('minimum_thickness', opts%minimum_thickness)
    call g%add('inset_m', opts%inset_m, unit='m')
    call g%add('compressive_strength_pa', opts%compressive_strength_pa, unit='Pa')
  end subroutine limit_table

  !> Read the optional &limit group of `path`; the inset defaults to &arch contact_inset_m.
  subroutine read_limit_group(path, cfg, opts, status)
    character(len=*), intent(in) :: path
    type(config_t), intent(in) :: cfg
    type(limit_options_t), intent(out), target :: opts
    type(status_t), intent(inout) :: status
    type(nml_group_t) :: g

    call limit_table(opts, g)
    call g%read(path, status)
    if (.not. status%ok) return
    if (opts%compressive_strength_pa == unset) then
      opts%compressive_strength_pa = 0.0_dp
    else
      call need(opts%compressive_strength_pa > 0.0_dp, path, 'limit', 'compressive_strength_pa', &
                opts%compressive_strength_pa, &
                'compressive_strength_pa > 0 (leave it out for blocks that do not crush)', status)
      if (.not. status%ok) return
    end if
    if (opts%inset_m == unset) opts%inset_m = cfg%arch%contact_inset_m
    call need(opts%inset_m >= 0.0_dp .and. opts%inset_m < 0.5_dp*cfg%arch%thickness_m, path, 'limit', 'inset_m', &
              opts%inset_m, '0 <= inset_m < thickness_m/2 = '//fmt_significant(0.5_dp*cfg%arch%thickness_m), status)
  end subroutine read_limit_group

  !> Build the assembly and run the analyses that apply (`lp%assembly` says which
  !> assembly: 'arch', 'restrained arch', 'wall' or 'polygon file'); refuse what the
  !> analyses do not model. With &load_cases, each case's LP study in `cases` and `lp`
  !> the governing one's.
  subroutine analyse(cfg, opts, arch, res, tmin, lp, cases, status)
    type(config_t), intent(in) :: cfg
    type(limit_options_t), intent(in) :: opts
    type(assembly_t), intent(out) :: arch
    type(limit_result_t), intent(out) :: res
    type(thickness_result_t), intent(out) :: tmin
    type(lp_study_t), intent(out) :: lp
    type(case_study_t), allocatable, intent(out) :: cases(:)
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: f, why
    type(status_t) :: lp_status

    allocate (cases(0))
    f = trim(cfg%source_file)
    ! A restrained arch: the brackets are driven blocks the LP takes like any other.
    if (cfg%wall%courses > 0 .or. len_trim(cfg%arch%polygon_file) > 0 .or. cfg%bridge%n_spans > 0 .or. &
        cfg%arch%restrained_springings /= springings_none) then
      call analyse_any_assembly(cfg, opts, arch, lp, cases, status)
      if (.not. status%ok) status%message = f//': '//trim(status%message)
      return
    end if
    associate (a => cfg%arch)
      ! Below, a mechanism has too few joints; above, the search takes too long.
      if (a%n_voussoirs < 3) then
        why = 'a four-hinge mechanism needs 3 voussoirs'
      else
        why = 'its exhaustive four-hinge search grows as n^4 (9 s at 200 voussoirs, 40 s at 300, minutes '// &
              'beyond), and a semicircle of 50 or 200 voussoirs has the same minimum thickness to 4 digits'
      end if
      call need_range('3 <= n_voussoirs <= '//itoa(max_limit_voussoirs), f, 'arch', 'n_voussoirs', a%n_voussoirs, &
                      status, note=' of voussoir-limit: '//why)
      if (status%ok .and. opts%minimum_thickness .and. a%n_voussoirs < 4) &
        call fail(status, f//': &arch n_voussoirs = 3: the minimum thickness needs n_voussoirs >= 4 '// &
                  '(an arch of 3 voussoirs stands at vanishing thickness); set &limit minimum_thickness = .false.')
      if (.not. status%ok) return
      call build_config_assembly(cfg, arch, status)
      call horizontal_capacity(arch, opts%inset_m, a%friction, res, status, a%joint_friction)
      if (status%ok .and. opts%minimum_thickness) then
        call thickness_search(a%embrace_deg, a%n_voussoirs, a%r_ext_m, opts%inset_m, tmin%ratio_ext, &
                              tmin%ratio_mean, tmin%hinges, tmin%sides, status)
        tmin%computed = status%ok
        if (.not. status%ok) status%message = trim(status%message)// &
          ' (set &limit minimum_thickness = .false. to skip it)'
      end if
      ! A load outside every block is an error of the input, not a note of the LP.
      if (status%ok .and. has_loads(cfg)) call check_loads_placed(cfg, arch, status)
      if (status%ok) then
        ! The four-hinge results stand even where the LP has no answer (an arch thinner
        ! than its minimum thickness): its reason is reported, not an error.
        call assembly_study(cfg, opts, arch, lp, cases, lp_status)
        if (.not. lp_status%ok) lp%note = trim(lp_status%message)
      end if
    end associate
    lp%assembly = 'arch'
    if (.not. status%ok) status%message = f//': '//trim(status%message)
  end subroutine analyse

  !> A &wall, a polygon file (its driven blocks the fixed supports) or an arch with
  !> restraint brackets (driven blocks against the outer faces of its springing
  !> voussoirs, which the four-hinge analysis and the minimum thickness do not model):
  !> the LP alone, whose refusals are errors here (there is nothing else to report).
  subroutine analyse_any_assembly(cfg, opts, asm, lp, cases, status)
    type(config_t), intent(in) :: cfg
    type(limit_options_t), intent(in) :: opts
    type(assembly_t), intent(out) :: asm
    type(lp_study_t), intent(out) :: lp
    type(case_study_t), allocatable, intent(out) :: cases(:)
    type(status_t), intent(inout) :: status
    allocate (cases(0))
    call build_config_assembly(cfg, asm, status)
    if (.not. status%ok) return
    ! The fill's weight stands on the ring, but under horizontal acceleration its mass would
    ! have to move with it, which this model of the fill does not carry.
    if (asm%has_fill .and. .not. any(cfg%load%point_load_live(1:cfg%load%n_point_loads))) then
      call fail(status, '&bridge fill_density_kg_m3 > 0 needs a live point load in &load: the fill is modelled '// &
                'as its weight and the spread of live loads through it, not as a mass that a horizontal '// &
                'acceleration would load (leave the fill out for the acceleration case)')
      return
    end if
    if (has_loads(cfg)) call check_loads_placed(cfg, asm, status)
    if (.not. status%ok) return
    call assembly_study(cfg, opts, asm, lp, cases, status)
    if (.not. status%ok) status%message = 'limit analysis by linear programming: '//trim(status%message)
    if (cfg%vehicle%given .and. status%ok .and. cfg%cases%n == 0) lp%live_load = vehicle_words(cfg%vehicle)// &
      ' '//lp%live_load(index(lp%live_load, '('):)
    if (cfg%bridge%n_spans > 0) then
      lp%assembly = 'bridge'
    else if (cfg%wall%courses > 0) then
      lp%assembly = 'wall'
    else if (len_trim(cfg%arch%polygon_file) > 0) then
      lp%assembly = 'polygon file'
    else
      lp%assembly = 'restrained arch'
    end if
  end subroutine analyse_any_assembly

  !> The LP study of `asm`: under horizontal acceleration without &load; under the loads
  !> of &load as given; or with &load_cases each case's (its live loads times gamma_q,
  !> every permanent load times gamma_g) in `cases` and `lp` the governing case's. A case
  !> the LP cannot solve fails `status`, named.
  subroutine assembly_study(cfg, opts, asm, lp, cases, status)
    type(config_t), intent(in) :: cfg
    type(limit_options_t), intent(in) :: opts
    type(assembly_t), intent(in) :: asm
    type(lp_study_t), intent(out) :: lp
    type(case_study_t), allocatable, intent(out) :: cases(:)
    type(status_t), intent(inout) :: status
    type(load_config_t) :: load
    integer :: k
    allocate (cases(cfg%cases%n))
    associate (a => cfg%arch, c => cfg%cases)
      if (.not. has_loads(cfg)) then
        call lp_study(asm, a%density_kg_m3, a%width_m, a%friction, opts%inset_m, lp, status, &
                      joint_friction=a%joint_friction, compressive_strength_pa=opts%compressive_strength_pa)
        return
      end if
      if (c%n == 0) then
        call lp_study(asm, a%density_kg_m3, a%width_m, a%friction, opts%inset_m, lp, status, cfg%load, &
                      a%joint_friction, opts%compressive_strength_pa)
        return
      end if
      do k = 1, c%n
        load = case_load(cfg%load, c, k)
        cases(k)%name = c%name(k)
        cases(k)%gamma_q = c%gamma_q(k)
        cases(k)%gamma_g = c%gamma_g(k)
        cases(k)%live_total_n = live_total_n(load)
        call lp_study(factored_assembly(asm, c%gamma_g(k)), c%gamma_g(k)*a%density_kg_m3, a%width_m, a%friction, &
                      opts%inset_m, cases(k)%lp, status, load, a%joint_friction, opts%compressive_strength_pa)
        if (.not. status%ok) then
          status%message = 'load case '//itoa(k)//" '"//trim(c%name(k))//"' (gamma_q "// &
                           fmt_significant(c%gamma_q(k), 6)//', gamma_g '//fmt_significant(c%gamma_g(k), 6)//'): '// &
                           trim(status%message)
          return
        end if
        if (cfg%vehicle%given) cases(k)%lp%live_load = vehicle_words(cfg%vehicle)//' '// &
          cases(k)%lp%live_load(index(cases(k)%lp%live_load, '('):)
        cases(k)%lp%live_load = "load case '"//trim(c%name(k))//"', the live loads times gamma_q = "// &
          fmt_significant(c%gamma_q(k), 6)//', every permanent load times gamma_g = '// &
          fmt_significant(c%gamma_g(k), 6)//': '//cases(k)%lp%live_load
      end do
    end associate
    lp = cases(governing_case(cases))%lp
  end subroutine assembly_study

  !> 'lambda x the vehicle of &vehicle (name, N axles, spacings), its axles as live loads'
  function vehicle_words(v) result(text)
    type(vehicle_config_t), intent(in) :: v
    character(len=:), allocatable :: text
    integer :: k
    text = 'lambda x the vehicle of &vehicle'
    if (len_trim(v%name) > 0) text = text//" '"//trim(v%name)//"'"
    text = text//' ('//itoa(v%n_axles)//' axles of '
    do k = 1, v%n_axles
      if (k > 1) text = text//', '
      text = text//fmt_significant(v%axle_load_kn(k), 6)
    end do
    text = text//' kN'
    if (v%n_axles > 1) then
      text = text//', spaced '
      do k = 1, v%n_axles - 1
        if (k > 1) text = text//', '
        text = text//fmt_significant(v%axle_spacing_m(k), 6)
      end do
      text = text//' m'
    end if
    if (v%effective_width_m > 0.0_dp) text = text//', each over an effective width of '// &
      fmt_significant(v%effective_width_m, 6)//' m'
    text = text//') as these live point loads on the strip'
  end function vehicle_words

  !> Every load of &load on a block, at every position of its path.
  subroutine check_loads_placed(cfg, asm, status)
    type(config_t), intent(in) :: cfg
    type(assembly_t), intent(in) :: asm
    type(status_t), intent(inout) :: status
    type(placed_loads_t) :: placed
    integer :: i
    if (cfg%load%path_points < 2) call place_loads(cfg%load, asm, 0.0_dp, placed, status)
    do i = 1, cfg%load%path_points
      if (.not. status%ok) return
      call place_loads(cfg%load, asm, path_position_m(cfg%load, i) - vehicle_x(cfg%load), placed, status)
    end do
  end subroutine check_loads_placed

end module voussoir_limit_study
