!> The result file of one run (layout: docs/results_format.md).
module voussoir_run_output
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t
  use voussoir_version, only: code_version
  use voussoir_config, only: config_t, config_entry_t, config_entries, config_to_nml
  use voussoir_assembly, only: assembly_t
  use voussoir_model, only: model_t
  use voussoir_simulation, only: run_result_t
  use voussoir_h5, only: hid_t, h5_create, h5_close, h5_group, h5_group_close, h5_write, h5_attr, &
                         h5_rename, utc_now
  implicit none
  private

  public :: write_run_file, write_provenance

contains

  !> Root attributes every result file carries, and the /config groups.
  subroutine write_provenance(file_id, producer, cfg)
    integer(hid_t), intent(in) :: file_id
    character(len=*), intent(in) :: producer
    type(config_t), intent(in) :: cfg
    type(config_entry_t), allocatable :: e(:)
    integer(hid_t) :: config_id, group_id
    integer :: k, ival
    real(dp) :: rval

    e = config_entries(cfg)
    call h5_attr(file_id, 'producer', producer)
    call h5_attr(file_id, 'code_version', code_version)
    call h5_attr(file_id, 'created_utc', trim(utc_now()))
    call h5_attr(file_id, 'config_nml', config_to_nml(e))
    call h5_attr(file_id, 'input_file', trim(cfg%source_file))
    call h5_group(file_id, 'config', config_id)
    do k = 1, size(e)
      call h5_group(config_id, trim(e(k)%group), group_id)
      select case (e(k)%kind)
      case ('r')
        read (e(k)%value, *) rval
        call h5_attr(group_id, trim(e(k)%name), rval)
      case ('i')
        read (e(k)%value, *) ival
        call h5_attr(group_id, trim(e(k)%name), ival)
      case ('l')
        call h5_attr(group_id, trim(e(k)%name), merge(1, 0, e(k)%value == '.true.'))
      case default
        call h5_attr(group_id, trim(e(k)%name), trim(e(k)%value))
      end select
      call h5_group_close(group_id)
    end do
    call h5_group_close(config_id)
  end subroutine write_provenance

  !> Write the run to `cfg%output%file` through a temporary file, so that a failure
  !> leaves no half-written result.
  subroutine write_run_file(cfg, assembly, model, res, status)
    type(config_t), intent(in) :: cfg
    type(assembly_t), intent(in) :: assembly
    type(model_t), intent(in) :: model
    type(run_result_t), intent(in) :: res
    type(status_t), intent(inout) :: status
    integer(hid_t) :: file_id, g
    character(len=:), allocatable :: path, tmp
    real(dp), allocatable :: verts(:, :, :)
    integer :: nb, i, nv, n

    path = trim(cfg%output%file)
    tmp = path//'.part'
    call h5_create(tmp, file_id, status)
    if (.not. status%ok) return
    call write_provenance(file_id, 'voussoir-run', cfg)

    call h5_group(file_id, 'result', g)
    call h5_attr(g, 'collapsed', merge(1, 0, res%collapsed))
    call h5_attr(g, 'collapse_time_s', res%collapse_time_s)
    call h5_attr(g, 'peak_crown_disp_m', res%peak_crown_disp_m)
    call h5_attr(g, 'mean_iterations', res%mean_iterations)
    call h5_attr(g, 'max_iterations', res%max_iterations)
    call h5_attr(g, 'nonconverged_steps', res%nonconverged_steps)
    call h5_attr(g, 'n_steps', res%n_steps)
    call h5_attr(g, 'wall_time_s', res%wall_time_s)
    call h5_group_close(g)

    call h5_write(file_id, 'time_s', res%time_s)
    call h5_group(file_id, 'table', g)
    call h5_write(g, 'x_m', res%table(1, :))
    call h5_write(g, 'v_m_s', res%table(2, :))
    call h5_write(g, 'a_m_s2', res%table(3, :))
    call h5_group_close(g)
    call h5_group(file_id, 'crown', g)
    call h5_write(g, 'dx_m', res%crown(1, :))
    call h5_write(g, 'dy_m', res%crown(2, :))
    call h5_group_close(g)

    nb = model%bodies%n
    call h5_group(file_id, 'bodies', g)
    call h5_write(g, 'position', res%q)
    allocate (verts(2, model%bodies%max_vertices, nb))
    verts = ieee_value(1.0_dp, ieee_quiet_nan)
    do i = 1, nb
      nv = model%bodies%n_vertices(i)
      verts(:, 1:nv, i) = model%bodies%vertex_local(:, 1:nv, i)
    end do
    call h5_write(g, 'vertices_local_m', verts)
    call h5_write(g, 'n_vertices', model%bodies%n_vertices)
    call h5_write(g, 'role', model%bodies%role)
    call h5_group_close(g)

    call h5_group(file_id, 'contacts', g)
    call h5_write(g, 'count', res%contact_count)
    call h5_group_close(g)
    call h5_group(file_id, 'solver', g)
    call h5_write(g, 'time_s', res%step_time_s)
    call h5_write(g, 'iterations', res%step_iterations)
    call h5_write(g, 'norm', res%step_norm)
    call h5_group_close(g)
    call h5_group(file_id, 'hinges', g)
    call h5_write(g, 'time_s', res%hinge_time_s)
    call h5_write(g, 'joint', res%hinge_joint)
    call h5_write(g, 'side', res%hinge_side)
    call h5_attr(g, 'side_names', '0=intrados,1=extrados')
    call h5_group_close(g)

    n = assembly%n_voussoirs
    if (n > 0) then
      call h5_group(file_id, 'arch', g)
      call h5_attr(g, 'n_voussoirs', n)
      call h5_attr(g, 'thickness_m', assembly%thickness_m)
      call h5_attr(g, 'r_ext_m', assembly%r_ext_m)
      call h5_attr(g, 'embrace_deg', cfg%arch%embrace_deg)
      call h5_write(g, 'joint_intrados_xy_m', assembly%joint_intrados_xy)
      call h5_write(g, 'joint_extrados_xy_m', assembly%joint_extrados_xy)
      call h5_group_close(g)
    end if
    call h5_close(file_id)
    call h5_rename(tmp, path, status)
  end subroutine write_run_file

end module voussoir_run_output
