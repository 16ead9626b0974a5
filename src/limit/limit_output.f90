!> What voussoir-limit prints: a readable table, or one JSON object
!> (docs/results_format.md, "voussoir-limit --json").
module voussoir_limit_output
  use voussoir_kinds, only: dp, g_m_s2
  use voussoir_config, only: config_t, has_loads, config_entries, config_to_nml
  use voussoir_text, only: itoa, int_list, fmt_json_real, json_string, json_bool, fmt_significant
  use voussoir_assembly, only: assembly_t
  use voussoir_limit_analysis, only: limit_result_t
  use voussoir_hinge_side, only: side_name
  use voussoir_limit_study, only: limit_options_t, thickness_result_t
  use voussoir_limit_lp_study, only: lp_study_t
  use voussoir_limit_lp_output, only: write_lp_table, lp_json
  use voussoir_limit_load_cases, only: case_study_t
  use voussoir_limit_case_output, only: write_cases_table, cases_json
  use voussoir_version, only: code_version
  use voussoir_bridge_config, only: bridge_config_t
  implicit none
  private

  public :: write_table, write_json

contains

  !> The readable report (with load cases, each case's LP table and their summary).
  subroutine write_table(u, path, cfg, opts, res, tmin, lp, cases)
    integer, intent(in) :: u
    character(len=*), intent(in) :: path
    type(config_t), intent(in) :: cfg
    type(limit_options_t), intent(in) :: opts
    type(limit_result_t), intent(in) :: res
    type(thickness_result_t), intent(in) :: tmin
    type(lp_study_t), intent(in) :: lp
    type(case_study_t), intent(in) :: cases(:)
    if (lp%assembly /= 'arch') then
      write (u, '(a)') 'voussoir-limit: '//path
      if (lp%assembly == 'restrained arch') then
        write (u, '(a)') "restrained arch (&arch restrained_springings = '"//trim(cfg%arch%restrained_springings)// &
          "'): the four-hinge analysis and the minimum thickness do not model the restraint brackets; the "// &
          'limit analysis by linear programming does (the brackets and foundations: fixed blocks)'
      else
        write (u, '(a)') lp%assembly//': the four-hinge analysis and the minimum thickness of an arch do not '// &
          'apply; the limit analysis by linear programming does (driven blocks: the fixed supports)'
      end if
      if (lp%assembly == 'bridge') then
        write (u, '(a)') '      interface inset '//fmt_significant(1.0e3_dp*opts%inset_m)//' mm, friction: ring '// &
          fmt_significant(cfg%bridge%ring_friction)//rings_words(cfg%bridge)//', piers '// &
          fmt_significant(cfg%bridge%pier_friction)//', skewbacks '//fmt_significant(cfg%bridge%abutment_friction)// &
          " (an interface takes the lesser of its two blocks'; the LP's heading below gives the ring's)"
      else
        write (u, '(a)') '      interface inset '//fmt_significant(1.0e3_dp*opts%inset_m)//' mm, friction '// &
          fmt_significant(cfg%arch%friction)
      end if
      if (size(cases) > 0) then
        call write_cases_table(u, cases, cfg%arch%friction)
      else
        call write_lp_table(u, lp, cfg%arch%friction)
      end if
      return
    end if
    associate (a => cfg%arch)
      write (u, '(a)') 'voussoir-limit: '//path
      write (u, '(a)') 'arch: '//itoa(a%n_voussoirs)//' voussoirs, embrace '//fmt_significant(a%embrace_deg)// &
        ' deg, r_ext '//fmt_significant(a%r_ext_m)//' m, thickness '//fmt_significant(a%thickness_m)//' m (t/R_ext '// &
        fmt_significant(a%thickness_m/a%r_ext_m)//')'
      write (u, '(a)') '      pivot inset '//fmt_significant(1.0e3_dp*opts%inset_m)//' mm, friction '//fmt_significant(a%friction)
      ! A load case comes first: the acceleration case of the weights alone is another
      ! question, printed after it and named as such.
      if (size(cases) > 0) then
        call write_cases_table(u, cases, a%friction)
      else if (.not. lp%live_is_acceleration) then
        call write_lp_table(u, lp, a%friction)
      end if
      call write_four_hinge(u, cfg, res, tmin, .not. lp%live_is_acceleration)
      if (lp%live_is_acceleration) call write_lp_table(u, lp, a%friction)
    end associate
  end subroutine write_table

  !> The four-hinge analysis of the arch under horizontal acceleration (its weights alone)
  !> and its minimum thickness; `after_load_case`: printed after the load case of &load,
  !> whose live loads it does not take.
  subroutine write_four_hinge(u, cfg, res, tmin, after_load_case)
    integer, intent(in) :: u
    type(config_t), intent(in) :: cfg
    type(limit_result_t), intent(in) :: res
    type(thickness_result_t), intent(in) :: tmin
    logical, intent(in) :: after_load_case
    character(len=*), parameter :: rule = '  ------------------------------------------------------------------'
    associate (a => cfg%arch)
      if (after_load_case) then
        write (u, '(/,a)') 'Not the load case above: the arch under horizontal acceleration, its weights alone '// &
          '(four-hinge analysis; rigid blocks, no tension, no sliding; load = lambda x weight, no &load)'
      else
        write (u, '(/,a)') 'Horizontal collapse (rigid blocks, no tension, no sliding; load = lambda x weight)'
      end if
      write (u, '(a)') '  direction  lambda     lambda g [m/s2]  mechanism (hinges from the left)'
      write (u, '(a)') rule
      call direction_row(u, '+x', res%lambda_pos, res%hinges_pos(1:res%n_hinges_pos), &
                         res%sides_pos(1:res%n_hinges_pos))
      call direction_row(u, '-x', res%lambda_neg, res%hinges_neg(1:res%n_hinges_neg), &
                         res%sides_neg(1:res%n_hinges_neg))
      if (res%n_hinges_pos == 0 .and. res%n_hinges_neg == 0) then
        write (u, '(a)') '  no mechanism opens: without sliding the blocks carry any horizontal load '// &
          '(no friction check)'
      else
        ! A direction without a mechanism has nothing to check.
        if ((res%bounds_meet_pos .or. res%n_hinges_pos == 0) .and. (res%bounds_meet_neg .or. res%n_hinges_neg == 0)) then
          write (u, '(a)') '  static check: the thrust line through the hinges stays inside every joint '// &
            '(bounds meet)'
        else
          write (u, '(a)') '  static check: the thrust line through the hinges leaves a joint '// &
            '(bounds do not meet: lambda is an upper bound only)'
        end if
        write (u, '(a)') '  friction check: '//friction_text(res, a%n_voussoirs, a%friction, &
                                                             any(a%joint_friction >= 0.0_dp))
        if (has_loads(cfg) .and. .not. after_load_case) write (u, '(a)') '  (the four-hinge analysis takes the '// &
          'weights alone: the dead loads of &load enter the linear programme below)'
      end if
      if (tmin%computed) then
        write (u, '(/,a)') 'Minimum thickness (same embrace, voussoirs, r_ext and inset; own weight only)'
        write (u, '(a,f9.6,a,f9.6,a)') '  t/R_ext ', tmin%ratio_ext, '   t/R_mean ', tmin%ratio_mean, &
          '   t_min '//fmt_significant(1.0e3_dp*tmin%ratio_ext*a%r_ext_m)//' mm'
        write (u, '(a)') '  hinges: '//hinge_text(tmin%hinges, tmin%sides)
      end if
    end associate
  end subroutine write_four_hinge

  !> One line of the capacity table.
  subroutine direction_row(u, name, lambda, hinges, sides)
    integer, intent(in) :: u
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: lambda
    integer, intent(in) :: hinges(:), sides(:)
    if (lambda == huge(1.0_dp)) then
      write (u, '(4x,a,7x,a)') name, 'no admissible mechanism'
      return
    end if
    write (u, '(4x,a,5x,f9.6,2x,f9.4,8x,a)') name, lambda, lambda*g_m_s2, hinge_text(hinges, sides)
    if (lambda < 0.0_dp) write (u, '(15x,a)') &
      '(negative: the arch cannot carry its own weight; it is thinner than its minimum thickness)'
  end subroutine direction_row

  !> ' (n rings, between them f)' for a multi-ring bridge, else ''.
  function rings_words(b) result(text)
    type(bridge_config_t), intent(in) :: b
    character(len=:), allocatable :: text
    text = ''
    if (b%n_rings > 1) text = ' ('//itoa(b%n_rings)//' rings, between them '//fmt_significant(b%ring_joint_friction)//')'
  end function rings_words

  !> 'joint 0 intrados, joint 5 extrados, ...'
  function hinge_text(hinges, sides) result(text)
    integer, intent(in) :: hinges(:), sides(:)
    character(len=:), allocatable :: text
    integer :: k
    text = ''
    do k = 1, size(hinges)
      if (k > 1) text = text//', '
      text = text//'joint '//itoa(hinges(k))//' '//side_name(sides(k))
    end do
  end function hinge_text

  !> 'hinging governs ...' or 'sliding governs at joints ...'.
  !> With `per_joint`, some joints have their own friction (&arch joint_friction), against
  !> which they were checked.
  function friction_text(res, n_voussoirs, friction, per_joint) result(text)
    type(limit_result_t), intent(in) :: res
    integer, intent(in) :: n_voussoirs
    real(dp), intent(in) :: friction
    logical, intent(in) :: per_joint
    character(len=:), allocatable :: text, coefficient
    integer, allocatable :: joints(:)
    real(dp) :: worst
    integer :: k
    call sliding_union(res, n_voussoirs, joints)
    worst = max(maxval(res%shear_ratio_pos), maxval(res%shear_ratio_neg))
    coefficient = 'friction '//fmt_significant(friction)
    if (per_joint) coefficient = 'the friction of each joint (joint_friction where set, else '//coefficient//')'
    if (size(joints) == 0) then
      text = 'hinging governs (largest |T|/N at collapse '//fmt_significant(worst, 5)//' <= '//coefficient//')'
    else
      text = 'sliding governs at joints '
      do k = 1, size(joints)
        if (k > 1) text = text//', '
        text = text//itoa(joints(k))
      end do
      if (worst == huge(1.0_dp)) then
        text = text//' (a joint is not in compression in the collapse state)'
      else
        text = text//' (|T|/N at collapse up to '//fmt_significant(worst, 5)//' > '//coefficient// &
               '): the true capacity can be lower than lambda'
      end if
    end if
  end function friction_text

  !> Joints where sliding governs in either direction, ascending.
  pure subroutine sliding_union(res, n_voussoirs, joints)
    type(limit_result_t), intent(in) :: res
    integer, intent(in) :: n_voussoirs
    integer, allocatable, intent(out) :: joints(:)
    integer :: j
    allocate (joints(0))
    do j = 0, n_voussoirs
      if (any(res%sliding_joints_pos == j) .or. any(res%sliding_joints_neg == j)) joints = [joints, j]
    end do
  end subroutine sliding_union

  !> The JSON object of docs/results_format.md.
  subroutine write_json(u, path, cfg, opts, arch, res, tmin, lp, cases)
    integer, intent(in) :: u
    character(len=*), intent(in) :: path
    type(config_t), intent(in) :: cfg
    type(limit_options_t), intent(in) :: opts
    type(assembly_t), intent(in) :: arch
    type(limit_result_t), intent(in) :: res
    type(thickness_result_t), intent(in) :: tmin
    type(lp_study_t), intent(in) :: lp
    type(case_study_t), intent(in) :: cases(:)  !! the load cases of &load_cases (lp: the governing one)
    integer, allocatable :: sliding(:)
    character(len=1), parameter :: nl = achar(10)
    character(len=:), allocatable :: text
    if (lp%assembly /= 'arch') then
      if (lp%assembly == 'restrained arch') then
        call write_json_any(u, path, cfg, lp, cases, arch_json(cfg, opts, arch), blocks_json(arch))
      else
        call write_json_any(u, path, cfg, lp, cases, 'null', blocks_json(arch))
      end if
      return
    end if
    call sliding_union(res, cfg%arch%n_voussoirs, sliding)
    associate (a => cfg%arch)
      text = '{'//nl// &
        '  "producer": "voussoir-limit",'//nl// &
        '  "code_version": '//json_string(code_version)//','//nl// &
        '  "input_file": '//json_string(path)//','//nl// &
        '  "config_nml": '//json_string(config_to_nml(config_entries(cfg)))//','//nl// &
        '  "g_m_s2": '//fmt_json_real(g_m_s2)//','//nl//lp_json(lp)//cases_json(cases)// &
        '  "blocks": '//blocks_json(arch)//','//nl// &
        '  "lambda_pos": '//finite_or_null(res%lambda_pos)//','//nl// &
        '  "lambda_neg": '//finite_or_null(res%lambda_neg)//','//nl// &
        '  "hinges_pos": '//hinge_json(res%hinges_pos(1:res%n_hinges_pos), res%sides_pos(1:res%n_hinges_pos))// &
        ','//nl// &
        '  "hinges_neg": '//hinge_json(res%hinges_neg(1:res%n_hinges_neg), res%sides_neg(1:res%n_hinges_neg))// &
        ','//nl// &
        '  "bounds_meet_pos": '//json_bool(res%bounds_meet_pos)//','//nl// &
        '  "bounds_meet_neg": '//json_bool(res%bounds_meet_neg)//','//nl
      if (tmin%computed) then
        text = text// &
          '  "min_thickness_ratio_ext": '//fmt_json_real(tmin%ratio_ext)//','//nl// &
          '  "min_thickness_ratio_mean": '//fmt_json_real(tmin%ratio_mean)//','//nl// &
          '  "min_thickness_m": '//fmt_json_real(tmin%ratio_ext*a%r_ext_m)//','//nl// &
          '  "hinges_min_thickness": '//hinge_json(tmin%hinges, tmin%sides)//','//nl
      else
        text = text// &
          '  "min_thickness_ratio_ext": null,'//nl//'  "min_thickness_ratio_mean": null,'//nl// &
          '  "min_thickness_m": null,'//nl//'  "hinges_min_thickness": [],'//nl
      end if
      text = text// &
        '  "friction": '//fmt_json_real(a%friction)//','//nl// &
        '  "sliding": ['//int_list(sliding)//'],'//nl// &
        '  "sliding_pos": ['//int_list(res%sliding_joints_pos)//'],'//nl// &
        '  "sliding_neg": ['//int_list(res%sliding_joints_neg)//'],'//nl// &
        '  "max_shear_ratio_pos": '//finite_or_null(maxval(res%shear_ratio_pos))//','//nl// &
        '  "max_shear_ratio_neg": '//finite_or_null(maxval(res%shear_ratio_neg))//','//nl// &
        '  "thrust_fraction_pos": '//fraction_list(res%thrust_fraction_pos)//','//nl// &
        '  "thrust_fraction_neg": '//fraction_list(res%thrust_fraction_neg)//','//nl// &
        '  "arch": '//arch_json(cfg, opts, arch)//nl//'}'
    end associate
    write (u, '(a)') text
  end subroutine write_json

  !> The "arch" object: its shape, the inset, and the ends of every joint.
  function arch_json(cfg, opts, arch) result(text)
    type(config_t), intent(in) :: cfg
    type(limit_options_t), intent(in) :: opts
    type(assembly_t), intent(in) :: arch
    character(len=:), allocatable :: text
    character(len=1), parameter :: nl = achar(10)
    integer :: j
    associate (a => cfg%arch)
      text = '{'//nl// &
        '    "n_voussoirs": '//itoa(a%n_voussoirs)//','//nl// &
        '    "embrace_deg": '//fmt_json_real(a%embrace_deg)//','//nl// &
        '    "r_ext_m": '//fmt_json_real(a%r_ext_m)//','//nl// &
        '    "thickness_m": '//fmt_json_real(a%thickness_m)//','//nl// &
        '    "contact_inset_m": '//fmt_json_real(opts%inset_m)//','//nl// &
        '    "joint_intrados_xy_m": ['
      do j = 0, a%n_voussoirs
        if (j > 0) text = text//', '
        text = text//'['//fmt_json_real(arch%joint_intrados_xy(1, j))//', '// &
               fmt_json_real(arch%joint_intrados_xy(2, j))//']'
      end do
      text = text//'],'//nl//'    "joint_extrados_xy_m": ['
      do j = 0, a%n_voussoirs
        if (j > 0) text = text//', '
        text = text//'['//fmt_json_real(arch%joint_extrados_xy(1, j))//', '// &
               fmt_json_real(arch%joint_extrados_xy(2, j))//']'
      end do
      text = text//']'//nl//'  }'
    end associate
  end function arch_json

  !> The "blocks" list: every block of the assembly as analysed, in body order (the
  !> numbers of "blocks" in contact_forces and point_loads, from 1), with its vertices
  !> (counter-clockwise) [m], whether it is driven (a fixed support) and, for a bridge,
  !> its name.
  function blocks_json(asm) result(text)
    type(assembly_t), intent(in) :: asm
    character(len=:), allocatable :: text
    integer :: b, k
    text = '['
    do b = 1, asm%n_bodies
      if (b > 1) text = text//', '
      text = text//'{"driven": '//json_bool(asm%driven(b))//', '
      if (allocated(asm%block_name)) text = text//'"name": '//json_string(trim(asm%block_name(b)))//', '
      text = text//'"vertices_xy_m": ['
      do k = 1, size(asm%polygon(b)%xy, 2)
        if (k > 1) text = text//', '
        text = text//'['//fmt_json_real(asm%polygon(b)%xy(1, k))//', '//fmt_json_real(asm%polygon(b)%xy(2, k))//']'
      end do
      text = text//']}'
    end do
    text = text//']'
  end function blocks_json

  !> The JSON of a wall, a polygon file or a restrained arch: every key of the arch's,
  !> null or empty where the four-hinge analysis of an arch does not apply (the "arch"
  !> object given for a restrained arch), and the LP's.
  subroutine write_json_any(u, path, cfg, lp, cases, arch_text, blocks_text)
    integer, intent(in) :: u
    character(len=*), intent(in) :: path
    type(config_t), intent(in) :: cfg
    type(lp_study_t), intent(in) :: lp
    type(case_study_t), intent(in) :: cases(:)
    character(len=*), intent(in) :: arch_text   !! the "arch" object of a restrained arch, else null
    character(len=*), intent(in) :: blocks_text !! the "blocks" list
    character(len=1), parameter :: nl = achar(10)
    write (u, '(a)') '{'//nl// &
      '  "producer": "voussoir-limit",'//nl// &
      '  "code_version": '//json_string(code_version)//','//nl// &
      '  "input_file": '//json_string(path)//','//nl// &
      '  "config_nml": '//json_string(config_to_nml(config_entries(cfg)))//','//nl// &
      '  "g_m_s2": '//fmt_json_real(g_m_s2)//','//nl//lp_json(lp)//cases_json(cases)// &
      '  "blocks": '//blocks_text//','//nl// &
      '  "lambda_pos": null,'//nl//'  "lambda_neg": null,'//nl// &
      '  "hinges_pos": [],'//nl//'  "hinges_neg": [],'//nl// &
      '  "bounds_meet_pos": false,'//nl//'  "bounds_meet_neg": false,'//nl// &
      '  "min_thickness_ratio_ext": null,'//nl//'  "min_thickness_ratio_mean": null,'//nl// &
      '  "min_thickness_m": null,'//nl//'  "hinges_min_thickness": [],'//nl// &
      '  "friction": '//fmt_json_real(cfg%arch%friction)//','//nl// &
      '  "sliding": [],'//nl//'  "sliding_pos": [],'//nl//'  "sliding_neg": [],'//nl// &
      '  "max_shear_ratio_pos": null,'//nl//'  "max_shear_ratio_neg": null,'//nl// &
      '  "thrust_fraction_pos": null,'//nl//'  "thrust_fraction_neg": null,'//nl// &
      '  "arch": '//arch_text//nl//'}'
  end subroutine write_json_any

  !> A number, or null for the module's `huge` (no admissible mechanism, joint not in
  !> compression).
  function finite_or_null(x) result(text)
    real(dp), intent(in) :: x
    character(len=:), allocatable :: text
    if (x == huge(1.0_dp)) then
      text = 'null'
    else
      text = fmt_json_real(x)
    end if
  end function finite_or_null

  !> Where the thrust crosses each joint (0 intrados pivot, 1 extrados pivot) as a JSON
  !> list; null where there is no thrust line (no mechanism in that direction).
  function fraction_list(f) result(text)
    real(dp), allocatable, intent(in) :: f(:)
    character(len=:), allocatable :: text
    integer :: k
    if (.not. allocated(f)) then
      text = 'null'
      return
    end if
    text = '['
    do k = lbound(f, 1), ubound(f, 1)
      if (k > lbound(f, 1)) text = text//', '
      text = text//finite_or_null(f(k))
    end do
    text = text//']'
  end function fraction_list

  function hinge_json(hinges, sides) result(text)
    integer, intent(in) :: hinges(:), sides(:)
    character(len=:), allocatable :: text
    integer :: k
    text = '['
    do k = 1, size(hinges)
      if (k > 1) text = text//', '
      text = text//'{"joint": '//itoa(hinges(k))//', "side": "'//side_name(sides(k))//'"}'
    end do
    text = text//']'
  end function hinge_json



end module voussoir_limit_output
