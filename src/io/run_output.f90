!> The result file of one run (layout: docs/results_format.md).
module voussoir_run_output
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use voussoir_kinds, only: dp, g_m_s2
  use voussoir_status, only: status_t
  use voussoir_version, only: code_version
  use voussoir_config, only: config_t, config_entry_t, config_entries, config_to_nml
  use voussoir_assembly, only: assembly_t
  use voussoir_model, only: model_t
  use voussoir_motion, only: waveform_accelerogram
  use voussoir_simulation, only: run_result_t
  use voussoir_hinge_side, only: side_file_code
  use voussoir_h5, only: hid_t, h5_create, h5_close, h5_group, h5_group_close, h5_write, h5_attr, &
                         h5_commit, utc_now
  implicit none
  private

  public :: write_run_file, write_provenance

contains

  !> Root attributes every result file carries, and the /config groups.
  subroutine write_provenance(file_id, producer, cfg, status)
    integer(hid_t), intent(in) :: file_id
    character(len=*), intent(in) :: producer
    type(config_t), intent(in) :: cfg
    type(status_t), intent(inout) :: status
    type(config_entry_t), allocatable :: e(:)
    integer(hid_t) :: config_id, group_id
    integer :: k, ival
    real(dp) :: rval

    allocate (e(0))   ! (gfortran warns of an unset descriptor otherwise)
    e = config_entries(cfg)
    call h5_attr(file_id, 'producer', producer, status)
    call h5_attr(file_id, 'code_version', code_version, status)
    call h5_attr(file_id, 'created_utc', trim(utc_now()), status)
    call h5_attr(file_id, 'config_nml', config_to_nml(e), status)
    call h5_attr(file_id, 'input_file', trim(cfg%source_file), status)
    call h5_group(file_id, 'config', config_id, status)
    do k = 1, size(e)
      call h5_group(config_id, trim(e(k)%group), group_id, status)
      select case (e(k)%kind)
      case ('r')
        read (e(k)%value, *) rval
        call h5_attr(group_id, trim(e(k)%name), rval, status)
      case ('i')
        read (e(k)%value, *) ival
        call h5_attr(group_id, trim(e(k)%name), ival, status)
      case ('l')
        call h5_attr(group_id, trim(e(k)%name), merge(1, 0, e(k)%value == '.true.'), status)
      case default
        call h5_attr(group_id, trim(e(k)%name), trim(e(k)%value), status)
      end select
      call h5_group_close(group_id, status)
    end do
    call h5_group_close(config_id, status)
  end subroutine write_provenance

  !> Write the run to `cfg%output%file`, whole or not at all (see voussoir_h5).
  subroutine write_run_file(cfg, assembly, model, res, status)
    type(config_t), intent(in) :: cfg
    type(assembly_t), intent(in) :: assembly
    type(model_t), intent(in) :: model
    type(run_result_t), intent(in) :: res
    type(status_t), intent(inout) :: status
    integer(hid_t) :: file_id, g
    character(len=:), allocatable :: path

    path = trim(cfg%output%file)
    call h5_create(path, file_id, status)
    if (.not. status%ok) return
    call write_provenance(file_id, 'voussoir-run', cfg, status)
    call write_result_summary(file_id, res, status)
    call write_samples(file_id, model, res, status)
    if (model%motion%waveform == waveform_accelerogram) call write_record(file_id, cfg, model, status)
    call write_contacts(file_id, model%solver%dt_s, res, status)
    call h5_group(file_id, 'solver', g, status)
    call h5_write(g, 'time_s', res%step_time_s, status)
    call h5_write(g, 'iterations', res%step_iterations, status)
    call h5_write(g, 'norm', res%step_norm, status)
    call h5_group_close(g, status)
    call h5_group(file_id, 'hinges', g, status)
    call h5_write(g, 'time_s', res%hinge_time_s, status)
    call h5_write(g, 'joint', res%hinge_joint, status)
    call h5_write(g, 'side', side_file_code(res%hinge_side), status)
    call h5_attr(g, 'side_names', '0=intrados,1=extrados', status)
    call h5_group_close(g, status)
    if (assembly%n_voussoirs > 0) call write_arch(file_id, cfg, assembly, status)
    call h5_commit(file_id, path, status)
  end subroutine write_run_file

  !> /result: what the run found (collapse, peak, residual) and how the solver did.
  subroutine write_result_summary(file_id, res, status)
    integer(hid_t), intent(in) :: file_id
    type(run_result_t), intent(in) :: res
    type(status_t), intent(inout) :: status
    integer(hid_t) :: g
    call h5_group(file_id, 'result', g, status)
    call h5_attr(g, 'collapsed', merge(1, 0, res%collapsed), status)
    call h5_attr(g, 'collapse_time_s', res%collapse_time_s, status)
    call h5_attr(g, 'peak_crown_disp_m', res%peak_crown_disp_m, status)
    call h5_attr(g, 'mean_iterations', res%mean_iterations, status)
    call h5_attr(g, 'max_iterations', res%max_iterations, status)
    call h5_attr(g, 'nonconverged_steps', res%nonconverged_steps, status)
    call h5_attr(g, 'n_steps', res%n_steps, status)
    ! The steps ridden at rest on the table (&solver rest_capacity_m_s2), not solved.
    call h5_attr(g, 'rest_steps', res%rest_steps, status)
    call h5_attr(g, 'ended_at_rest', merge(1, 0, res%ended_at_rest), status)
    call h5_attr(g, 'wall_time_s', res%wall_time_s, status)
    ! 0: the run went to its end; else the signal (2 SIGINT, 15 SIGTERM) that stopped it
    ! early: the file holds what was computed until then.
    call h5_attr(g, 'interrupted_by_signal', res%interrupted_by, status)
    ! The largest final displacement of a free block relative to the table, and its body.
    call h5_attr(g, 'max_residual_disp_m', res%max_residual_disp_m, status)
    call h5_attr(g, 'max_residual_body', res%max_residual_body, status)
    call h5_group_close(g, status)
  end subroutine write_result_summary

  !> The samples: /time_s, /table, /crown, and /bodies with the blocks' shapes.
  subroutine write_samples(file_id, model, res, status)
    integer(hid_t), intent(in) :: file_id
    type(model_t), intent(in) :: model
    type(run_result_t), intent(in) :: res
    type(status_t), intent(inout) :: status
    integer(hid_t) :: g
    real(dp), allocatable :: verts(:, :, :)
    integer :: nb, i, nv

    call h5_write(file_id, 'time_s', res%time_s, status)
    call h5_group(file_id, 'table', g, status)
    call h5_write(g, 'x_m', res%table(1, :), status)
    call h5_write(g, 'v_m_s', res%table(2, :), status)
    call h5_write(g, 'a_m_s2', res%table(3, :), status)
    if (allocated(res%table_vertical)) then
      call h5_write(g, 'y_m', res%table_vertical(1, :), status)
      call h5_write(g, 'vy_m_s', res%table_vertical(2, :), status)
      call h5_write(g, 'ay_m_s2', res%table_vertical(3, :), status)
    end if
    call h5_group_close(g, status)
    call h5_group(file_id, 'crown', g, status)
    call h5_write(g, 'dx_m', res%crown(1, :), status)
    call h5_write(g, 'dy_m', res%crown(2, :), status)
    call h5_group_close(g, status)

    nb = model%bodies%n
    call h5_group(file_id, 'bodies', g, status)
    call h5_write(g, 'position', res%q, status)
    allocate (verts(2, model%bodies%max_vertices, nb))
    verts = ieee_value(1.0_dp, ieee_quiet_nan)
    do i = 1, nb
      nv = model%bodies%n_vertices(i)
      verts(:, 1:nv, i) = model%bodies%vertex_local(:, 1:nv, i)
    end do
    call h5_write(g, 'vertices_local_m', verts, status)
    call h5_write(g, 'n_vertices', model%bodies%n_vertices, status)
    call h5_write(g, 'role', model%bodies%role, status)
    call h5_group_close(g, status)
  end subroutine write_samples

  !> /contacts: the contacts that carry load at every sample, one flat list with the
  !> offsets of each sample, their impulses over the step and mean forces (impulse / dt_s).
  subroutine write_contacts(file_id, dt_s, res, status)
    integer(hid_t), intent(in) :: file_id
    real(dp), intent(in) :: dt_s
    type(run_result_t), intent(in) :: res
    type(status_t), intent(inout) :: status
    integer(hid_t) :: g
    integer :: m
    m = res%n_contact_records   ! the record's arrays may be longer (room reserved)
    call h5_group(file_id, 'contacts', g, status)
    call h5_attr(g, 'dt_s', dt_s, status)
    call h5_write(g, 'count', res%contact_count, status)
    if (.not. res%contacts_recorded) then   ! a run that did not keep them (none writes a file today)
      call h5_group_close(g, status)
      return
    end if
    call h5_write(g, 'start', res%contact_start - 1, status)   ! 0-based offsets for Python
    call h5_write(g, 'body', res%contact_bodies(:, 1:m), status)
    call h5_write(g, 'joint', res%contact_joint(1:m), status)
    call h5_write(g, 'point_m', res%contact_point(:, 1:m), status)
    call h5_write(g, 'normal', res%contact_normal(:, 1:m), status)
    call h5_write(g, 'normal_impulse_n_s', res%contact_impulse(2, 1:m), status)
    call h5_write(g, 'tangent_impulse_n_s', res%contact_impulse(1, 1:m), status)
    call h5_write(g, 'normal_force_n', res%contact_impulse(2, 1:m)/dt_s, status)
    call h5_write(g, 'tangent_force_n', res%contact_impulse(1, 1:m)/dt_s, status)
    call h5_group_close(g, status)
  end subroutine write_contacts

  !> /record: the accelerogram a run was driven by and its intensity measures.
  subroutine write_record(file_id, cfg, model, status)
    integer(hid_t), intent(in) :: file_id
    type(config_t), intent(in) :: cfg
    type(model_t), intent(in) :: model
    type(status_t), intent(inout) :: status
    integer(hid_t) :: g
    call h5_group(file_id, 'record', g, status)
    call h5_attr(g, 'name', trim(model%motion%record_name), status)
    call h5_attr(g, 'description', trim(model%motion%record_description), status)
    call h5_attr(g, 'file', trim(cfg%motion%record_file), status)
    call h5_attr(g, 'scale', cfg%motion%record_scale, status)
    call h5_attr(g, 'n_samples', size(model%motion%a_m_s2), status)
    call h5_attr(g, 'dt_s', model%motion%dt_record_s, status)
    call h5_attr(g, 'start_s', model%motion%start_s, status)
    associate (im => model%motion%intensity)
      call h5_attr(g, 'pga_m_s2', im%pga_m_s2, status)
      call h5_attr(g, 'pga_g', im%pga_m_s2/g_m_s2, status)
      call h5_attr(g, 'pgv_m_s', im%pgv_m_s, status)
      call h5_attr(g, 'arias_m_s', im%arias_m_s, status)
      call h5_attr(g, 't5_s', im%t5_s, status)
      call h5_attr(g, 't95_s', im%t95_s, status)
      call h5_attr(g, 'significant_duration_s', im%significant_duration_s, status)
    end associate
    call h5_group_close(g, status)
  end subroutine write_record

  !> /arch: the arch's description and the ends of its joints.
  subroutine write_arch(file_id, cfg, assembly, status)
    integer(hid_t), intent(in) :: file_id
    type(config_t), intent(in) :: cfg
    type(assembly_t), intent(in) :: assembly
    type(status_t), intent(inout) :: status
    integer(hid_t) :: g
    call h5_group(file_id, 'arch', g, status)
    call h5_attr(g, 'n_voussoirs', assembly%n_voussoirs, status)
    call h5_attr(g, 'thickness_m', assembly%thickness_m, status)
    call h5_attr(g, 'r_ext_m', assembly%r_ext_m, status)
    call h5_attr(g, 'embrace_deg', cfg%arch%embrace_deg, status)
    call h5_write(g, 'joint_intrados_xy_m', assembly%joint_intrados_xy, status)
    call h5_write(g, 'joint_extrados_xy_m', assembly%joint_extrados_xy, status)
    call h5_group_close(g, status)
  end subroutine write_arch

end module voussoir_run_output
