!> What voussoir-limit prints of the limit analysis by linear programming: its lines of
!> the table and its keys of the JSON object (docs/results_format.md).
module voussoir_limit_lp_output
  use voussoir_kinds, only: dp, g_m_s2
  use voussoir_text, only: itoa, fmt_json_real, json_string, json_bool, fmt_significant
  use voussoir_hinge_side, only: side_name
  use voussoir_limit_lp, only: lp_result_t, joint_mode_name, joint_closed, joint_hinge
  use voussoir_limit_lp_study, only: lp_study_t, lp_direction_t
  use voussoir_placed_loads, only: kind_point, kind_fill, placed_loads_t, boussinesq_cutoff
  implicit none
  private

  public :: write_lp_table, lp_json, curve_json

contains

  !> The LP's part of the table.
  subroutine write_lp_table(u, lp, friction)
    integer, intent(in) :: u
    type(lp_study_t), intent(in) :: lp
    real(dp), intent(in) :: friction
    integer :: i
    write (u, '(/,a)') 'Limit analysis by linear programming (GLPK; rigid blocks, no tension, Coulomb friction '// &
      fmt_significant(friction)//')'
    if (allocated(lp%live_load)) write (u, '(a)') '  live load: '//lp%live_load
    write (u, '(a)') '  '//itoa(lp%faces%n)//' interfaces'
    if (allocated(lp%crush%face_strength_pa)) write (u, '(a)') '  compressive strength by part (&bridge): '// &
      itoa(count(lp%crush%face_strength_pa > 0.0_dp))//' of the interfaces crush, each at the lesser of its two '// &
      'blocks'' sigma_c ('//fmt_significant(minval(lp%crush%face_strength_pa, mask=lp%crush%face_strength_pa > 0.0_dp), 6)// &
      ' to '//fmt_significant(maxval(lp%crush%face_strength_pa), 6)//' Pa), its force kept N / (2 sigma_c w) from '// &
      'the ends (iterated: '//itoa(lp%crushing_steps)//' LPs'//trim(merge('             ', ', UNCONVERGED', &
      lp%crushing_converged))//')'
    if (lp%crush%strength_pa > 0.0_dp) write (u, '(a)') '  compressive strength '// &
      fmt_significant(lp%crush%strength_pa, 6)//' Pa: each interface force kept N / (2 sigma_c w) from the ends '// &
      '(iterated: '//itoa(lp%crushing_steps)//' LPs'//trim(merge('             ', ', UNCONVERGED', &
      lp%crushing_converged))//trim(merge(', an interface crushed through', '                              ', &
      lp%crushed_through))//')'
    if (lp%has_path) then
      write (u, '(a)') '  load factor along the path (x of the vehicle: the resultant of its live loads [m], associative lambda;'
      write (u, '(a)') '  "joint": a live load stands over the end of a joint on the top surface, added to the grid):'
      do i = 1, size(lp%curve_x_m)
        if (lp%curve_load_factor(i) < 0.0_dp) then
          write (u, '(a)') '    '//fmt_significant(lp%curve_x_m(i), 6)//'  none (no mechanism opens)'// &
            trim(merge('  joint', '       ', lp%curve_at_joint(i)))
        else
          write (u, '(a)') '    '//fmt_significant(lp%curve_x_m(i), 6)//'  '// &
            fmt_significant(lp%curve_load_factor(i), 7)//trim(merge('  joint', '       ', lp%curve_at_joint(i)))
        end if
      end do
      write (u, '(a)') '  critical position: x = '//fmt_significant(lp%critical_x_m, 6)//' m (the results below)'
    end if
    if (.not. lp%solved) then
      write (u, '(a)') '  no load factor: '//lp%note
      return
    end if
    call write_direction(u, lp, lp%assoc, lp%nonassociative_solved, lp%nonassoc, lp%steps, lp%converged)
    if (.not. lp%neg%applies) return
    write (u, '(a)') '  towards -x (the acceleration turned round):'
    if (.not. lp%neg%solved) then
      write (u, '(a)') '  no load factor: '//lp%neg%note
      return
    end if
    call write_direction(u, lp, lp%neg%assoc, lp%neg%nonassociative_solved, lp%neg%nonassoc, lp%neg%steps, &
                         lp%neg%converged)
  end subroutine write_lp_table

  !> The lines of one direction: both load factors and their mechanisms.
  subroutine write_direction(u, lp, assoc, nonassociative_solved, nonassoc, steps, converged)
    integer, intent(in) :: u
    type(lp_study_t), intent(in) :: lp
    type(lp_result_t), intent(in) :: assoc, nonassoc
    logical, intent(in) :: nonassociative_solved, converged
    integer, intent(in) :: steps
    write (u, '(a)') '  associative (sliding dilates):  lambda '//fmt_significant(assoc%load_factor, 7)// &
      ' (upper bound of its mechanism '//fmt_significant(assoc%load_factor_upper, 7)//')'// &
      acceleration_text(lp, assoc%load_factor)
    write (u, '(a)') '    mechanism: '//mechanism_text(lp, assoc)
    if (nonassociative_solved) then
      write (u, '(a)') '  non-associative (no dilatancy): lambda '//fmt_significant(nonassoc%load_factor, 7)// &
        acceleration_text(lp, nonassoc%load_factor)//' ('//itoa(steps)//' steps'// &
        trim(merge('             ', ', UNCONVERGED', converged))//')'
      write (u, '(a)') '    mechanism: '//mechanism_text(lp, nonassoc)
    else
      write (u, '(a)') '  non-associative: no solution (a step of the iteration has none)'
    end if
  end subroutine write_direction

  !> ', lambda g 3.69 m/s2' where the live load is the horizontal acceleration, else ''.
  function acceleration_text(lp, lambda) result(text)
    type(lp_study_t), intent(in) :: lp
    real(dp), intent(in) :: lambda
    character(len=:), allocatable :: text
    text = ''
    if (lp%live_is_acceleration) text = ', lambda g '//fmt_significant(lambda*g_m_s2, 5)//' m/s2'
  end function acceleration_text

  !> The moving joints: 'joint 5 hinge extrados, blocks 3-4 sliding, ...'
  function mechanism_text(lp, r) result(text)
    type(lp_study_t), intent(in) :: lp
    type(lp_result_t), intent(in) :: r
    character(len=:), allocatable :: text
    integer :: k
    text = ''
    do k = 1, lp%faces%n
      if (r%mode(k) == joint_closed) cycle
      if (len(text) > 0) text = text//', '
      text = text//joint_name(lp, k)//' '//joint_mode_name(r%mode(k))
      if (r%mode(k) == joint_hinge .and. lp%joint(k) >= 0) text = text//' '//side_name(lp%end_side(r%pivot_end(k), k))
    end do
    if (len(text) == 0) text = 'none (every joint closed)'
  end function mechanism_text

  function joint_name(lp, k) result(text)
    type(lp_study_t), intent(in) :: lp
    integer, intent(in) :: k
    character(len=:), allocatable :: text
    if (lp%joint(k) >= 0) then
      text = 'joint '//itoa(lp%joint(k))
    else
      text = 'blocks '//itoa(lp%faces%body(1, k))//'-'//itoa(lp%faces%body(2, k))
      if (allocated(lp%block_name)) text = text//' ('//trim(lp%block_name(lp%faces%body(1, k)))//' / '// &
        trim(lp%block_name(lp%faces%body(2, k)))//')'
    end if
  end function joint_name

  !> The LP's keys of the JSON object, each line ending with a comma.
  function lp_json(lp) result(text)
    type(lp_study_t), intent(in) :: lp
    character(len=:), allocatable :: text
    character(len=1), parameter :: nl = achar(10)
    integer :: i
    text = '  "assembly": '//json_string(lp%assembly)//','//nl
    if (allocated(lp%live_load)) then
      text = text//'  "live_load": '//json_string(lp%live_load)//','//nl
    else
      text = text//'  "live_load": null,'//nl
    end if
    text = text//'  "point_loads": '//point_loads_json(lp)//','//nl//fill_json(lp)//'  "critical_position": '
    if (lp%has_path) then
      text = text//'{"x_m": '//fmt_json_real(lp%critical_x_m)//', "load_factor": '// &
             fmt_json_real(lp%critical_load_factor)//'},'//nl
    else
      text = text//'null,'//nl
    end if
    text = text//'  "load_factor_curve": '//curve_json(lp)//','//nl
    if (lp%crush%strength_pa > 0.0_dp) then
      text = text//'  "compressive_strength_pa": '//fmt_json_real(lp%crush%strength_pa)//','//nl
    else
      text = text//'  "compressive_strength_pa": null,'//nl
    end if
    if (allocated(lp%crush%face_strength_pa)) then   ! each interface's, in the order of contact_forces
      text = text//'  "interface_compressive_strength_pa": ['
      do i = 1, size(lp%crush%face_strength_pa)
        text = text//trim(merge('null', '    ', lp%crush%face_strength_pa(i) <= 0.0_dp))
        if (lp%crush%face_strength_pa(i) > 0.0_dp) text = text//fmt_json_real(lp%crush%face_strength_pa(i))
        if (i < size(lp%crush%face_strength_pa)) text = text//', '
      end do
      text = text//'],'//nl
    end if
    text = text//'  "crushing_steps": '//itoa(lp%crushing_steps)//','//nl// &
           '  "crushing_converged": '//json_bool(lp%crushing_converged)//','//nl// &
           '  "crushed_through": '//json_bool(lp%crushed_through .or. lp%neg%crushed_through)//','//nl
    text = text//direction_json(lp, '', lp%solved, lp%note, lp%assoc, lp%nonassociative_solved, lp%nonassoc, &
                                lp%steps, lp%converged)
    ! The -x direction: the same keys ending in _neg (null where it does not apply).
    if (lp%neg%applies) then
      text = text//'  "live_load_neg": '//json_string('horizontal acceleration lambda g towards -x (lambda x the '// &
             'weight of each block)')//','//nl
    else
      text = text//'  "live_load_neg": null,'//nl
    end if
    text = text//direction_json(lp, '_neg', lp%neg%solved, lp%neg%note, lp%neg%assoc, lp%neg%nonassociative_solved, &
                                lp%neg%nonassoc, lp%neg%steps, lp%neg%converged)
  end function lp_json

  !> The keys of one direction, each name ending in `suffix`: both load factors, the note
  !> where there is none (an absent note: the +x analysis had no answer, so -x was not
  !> made), the mechanisms and contact forces.
  function direction_json(lp, suffix, solved, note, assoc, nonassociative_solved, nonassoc, steps, converged) &
    result(text)
    type(lp_study_t), intent(in) :: lp
    character(len=*), intent(in) :: suffix
    logical, intent(in) :: solved, nonassociative_solved, converged
    character(len=*), intent(in), optional :: note
    type(lp_result_t), intent(in) :: assoc, nonassoc
    integer, intent(in) :: steps
    character(len=:), allocatable :: text
    character(len=1), parameter :: nl = achar(10)
    if (solved) then
      text = '  "load_factor'//suffix//'": '//fmt_json_real(assoc%load_factor)//','//nl// &
        '  "load_factor_upper'//suffix//'": '//fmt_json_real(assoc%load_factor_upper)//','//nl// &
        '  "load_factor_note'//suffix//'": null,'//nl// &
        '  "mechanism'//suffix//'": '//mechanism_json(lp, assoc)//','//nl// &
        '  "contact_forces'//suffix//'": '//forces_json(lp, assoc)//','//nl
    else
      text = '  "load_factor'//suffix//'": null,'//nl//'  "load_factor_upper'//suffix//'": null,'//nl// &
        '  "load_factor_note'//suffix//'": '//json_string(note_text(note))//','//nl// &
        '  "mechanism'//suffix//'": [],'//nl//'  "contact_forces'//suffix//'": [],'//nl
    end if
    if (nonassociative_solved) then
      text = text//'  "load_factor_nonassociative'//suffix//'": '//fmt_json_real(nonassoc%load_factor)//','//nl// &
        '  "nonassociative_steps'//suffix//'": '//itoa(steps)//','//nl// &
        '  "nonassociative_converged'//suffix//'": '//json_bool(converged)//','//nl// &
        '  "mechanism_nonassociative'//suffix//'": '//mechanism_json(lp, nonassoc)//','//nl// &
        '  "contact_forces_nonassociative'//suffix//'": '//forces_json(lp, nonassoc)//','//nl
    else
      text = text//'  "load_factor_nonassociative'//suffix//'": null,'//nl//'  "nonassociative_steps'//suffix// &
        '": '//itoa(steps)//','//nl//'  "nonassociative_converged'//suffix//'": false,'//nl// &
        '  "mechanism_nonassociative'//suffix//'": [],'//nl//'  "contact_forces_nonassociative'//suffix//'": [],'//nl
    end if
  end function direction_json

  function note_text(note) result(text)
    character(len=*), intent(in), optional :: note
    character(len=:), allocatable :: text
    text = 'no analysis: the +x one has no answer'
    if (present(note)) text = note
  end function note_text

  !> One object per interface: its blocks, its arch joint (or null), its mode and, for a
  !> hinge, the side (arches) and the point it turns about.
  function mechanism_json(lp, r) result(text)
    type(lp_study_t), intent(in) :: lp
    type(lp_result_t), intent(in) :: r
    character(len=:), allocatable :: text
    integer :: k
    text = '['
    do k = 1, lp%faces%n
      if (k > 1) text = text//', '
      text = text//'{'//joint_keys(lp, k)//', "mode": "'//joint_mode_name(r%mode(k))//'", "hinge_side": '
      if (r%mode(k) == joint_hinge .and. lp%joint(k) >= 0) then
        text = text//'"'//side_name(lp%end_side(r%pivot_end(k), k))//'"'
      else
        text = text//'null'
      end if
      text = text//', "hinge_xy_m": '
      if (r%mode(k) == joint_hinge) then
        text = text//xy_json(r%end_xy(:, r%pivot_end(k), k))//'}'
      else
        text = text//'null}'
      end if
    end do
    text = text//']'
  end function mechanism_json

  !> One object per interface: the two ends (moved in by the crushing offsets where the
  !> strength is finite), the unit normal (from the first block into the second), the
  !> normal force at each end and the shear force [N] on the second block.
  function forces_json(lp, r) result(text)
    type(lp_study_t), intent(in) :: lp
    type(lp_result_t), intent(in) :: r
    character(len=:), allocatable :: text
    integer :: k
    text = '['
    do k = 1, lp%faces%n
      if (k > 1) text = text//', '
      text = text//'{'//joint_keys(lp, k)//', "ends_xy_m": ['//xy_json(r%end_xy(:, 1, k))//', '// &
        xy_json(r%end_xy(:, 2, k))//'], "normal": '//xy_json(lp%faces%normal(:, k))// &
        ', "normal_n": '//xy_json(r%normal_n(:, k))//', "shear_n": '//fmt_json_real(r%shear_n(k))//'}'
    end do
    text = text//']'
  end function forces_json

  !> The point loads of &load as placed (the distributed dead load's strips, the fill's
  !> weight and a live load's strips through the fill left out): the load j, the block,
  !> the point, the force [N] (a live one at load factor 1).
  function point_loads_json(lp) result(text)
    type(lp_study_t), intent(in) :: lp
    character(len=:), allocatable :: text
    integer :: k
    text = '['
    if (allocated(lp%placed%kind)) then
      do k = 1, lp%placed%n
        if (lp%placed%kind(k) /= kind_point) cycle
        if (len(text) > 1) text = text//', '
        text = text//'{"load": '//itoa(lp%placed%source(k))//', "block": '//itoa(lp%placed%block(k))// &
               ', "xy_m": '//xy_json(lp%placed%xy(:, k))//', "force_n": '//xy_json(lp%placed%force_n(:, k))// &
               ', "live": '//json_bool(lp%placed%live(k))//'}'
      end do
    end if
    text = text//']'
  end function point_loads_json

  !> With a fill: each live load on the fill's surface (load j, point, force [N] at load
  !> factor 1) and the x it spreads over on the blocks; and the fill's weight on each top
  !> face of a block (block, point, force [N]).
  function fill_json(lp) result(text)
    type(lp_study_t), intent(in) :: lp
    character(len=:), allocatable :: text
    character(len=1), parameter :: nl = achar(10)
    integer :: k
    logical :: first
    text = '  "surface_loads": ['//surface_json(lp, .true.)//'],'//nl//'  "patch_loads": ['//surface_json(lp, .false.)
    text = text//'],'//nl//'  "fill_loads": ['
    first = .true.
    if (allocated(lp%placed%kind)) then
      do k = 1, lp%placed%n
        if (lp%placed%kind(k) /= kind_fill) cycle
        if (.not. first) text = text//', '
        first = .false.
        text = text//'{"block": '//itoa(lp%placed%block(k))//', "xy_m": '//xy_json(lp%placed%xy(:, k))// &
               ', "force_n": '//xy_json(lp%placed%force_n(:, k))//'}'
      end do
    end if
    text = text//'],'//nl//'  "fill_pressures": ['
    if (allocated(lp%placed%pressure_block)) then
      do k = 1, lp%placed%n_pressure
        if (k > 1) text = text//', '
        text = text//'{"block": '//itoa(lp%placed%pressure_block(k))//', "xy_m": '// &
               xy_json(lp%placed%pressure_xy(:, k))//', "direction": '//xy_json(lp%placed%pressure_dir(:, k))// &
               ', "active_n": '//fmt_json_real(lp%placed%pressure_lo_n(k))//', "passive_n": '// &
               fmt_json_real(lp%placed%pressure_hi_n(k))//', "at_collapse_n": '
        if (lp%solved .and. allocated(lp%assoc%bounded_n)) then
          text = text//fmt_json_real(lp%assoc%bounded_n(k))//'}'
        else
          text = text//'null}'
        end if
      end do
    end if
    text = text//'],'//nl
  end function fill_json

  !> The surface loads of `lp` (each {load, xy_m, force_n, spread_x_m, patch_m}) if they
  !> stand on a fill (`on_fill`) or, without one, on the top surface (live patches).
  function surface_json(lp, on_fill) result(text)
    type(lp_study_t), intent(in) :: lp
    logical, intent(in) :: on_fill
    character(len=:), allocatable :: text
    integer :: k
    text = ''
    if (.not. allocated(lp%placed%surface_source)) return
    if (lp%placed%surface_on_fill .neqv. on_fill) return
    do k = 1, lp%placed%n_surface
      if (k > 1) text = text//', '
      text = text//'{"load": '//itoa(lp%placed%surface_source(k))//', "xy_m": '// &
             xy_json(lp%placed%surface_xy(:, k))//', "force_n": '//xy_json(lp%placed%surface_force_n(:, k))// &
             ', "spread_x_m": '//xy_json(lp%placed%surface_spread_x_m(:, k))//', "patch_m": '// &
             fmt_json_real(lp%placed%surface_patch_m(k))
      if (lp%placed%surface_boussinesq .and. on_fill) text = text//boussinesq_json(lp%placed, k)
      text = text//'}'
    end do
  end function surface_json

  !> Surface load k spread by Boussinesq: the cutoff, the fraction of the load Flamant's
  !> stress puts within the spread (before the strips are scaled to the load), each strip's
  !> load [N, down, at load factor 1] and the strips' ends along x [m], from the spread's
  !> first x to its last.
  function boussinesq_json(placed, k) result(text)
    type(placed_loads_t), intent(in) :: placed
    integer, intent(in) :: k
    character(len=:), allocatable :: text
    integer :: s, first_edge
    text = ', "dispersion": "boussinesq", "cutoff": '//fmt_json_real(boussinesq_cutoff)//', "retained": '// &
           fmt_json_real(placed%surface_retained(k))//', "strip_load_n": ['
    do s = placed%surface_first(k), placed%surface_first(k) + placed%surface_strips(k) - 1
      if (s > placed%surface_first(k)) text = text//', '
      text = text//fmt_json_real(-placed%force_n(2, s))
    end do
    text = text//'], "strip_edges_x_m": ['
    first_edge = sum(placed%surface_strips(1:k - 1) + 1)
    do s = 1, placed%surface_strips(k) + 1
      if (s > 1) text = text//', '
      text = text//fmt_json_real(placed%surface_edges_x_m(first_edge + s))
    end do
    text = text//']'
  end function boussinesq_json

  !> [{"x_m": .., "load_factor": ..}, ...] along the path (null where no mechanism opens).
  function curve_json(lp) result(text)
    type(lp_study_t), intent(in) :: lp
    character(len=:), allocatable :: text
    integer :: i
    text = '['
    if (lp%has_path) then
      do i = 1, size(lp%curve_x_m)
        if (i > 1) text = text//', '
        text = text//'{"x_m": '//fmt_json_real(lp%curve_x_m(i))//', "at_joint": '//json_bool(lp%curve_at_joint(i))// &
               ', "load_factor": '
        if (lp%curve_load_factor(i) < 0.0_dp) then
          text = text//'null}'
        else
          text = text//fmt_json_real(lp%curve_load_factor(i))//'}'
        end if
      end do
    end if
    text = text//']'
  end function curve_json

  function joint_keys(lp, k) result(text)
    type(lp_study_t), intent(in) :: lp
    integer, intent(in) :: k
    character(len=:), allocatable :: text
    text = '"blocks": ['//itoa(lp%faces%body(1, k))//', '//itoa(lp%faces%body(2, k))//'], "joint": '
    if (lp%joint(k) >= 0) then
      text = text//itoa(lp%joint(k))
    else
      text = text//'null'
    end if
  end function joint_keys

  function xy_json(xy) result(text)
    real(dp), intent(in) :: xy(2)
    character(len=:), allocatable :: text
    text = '['//fmt_json_real(xy(1))//', '//fmt_json_real(xy(2))//']'
  end function xy_json

end module voussoir_limit_lp_output
