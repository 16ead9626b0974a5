!> The time-step check of an IDA: a sample of the runs that bracket the thresholds,
!> redone at half the time step (rank 0, after the searches; no MPI).
module voussoir_sweep_dt_check
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t
  use voussoir_text, only: itoa
  use voussoir_config, only: config_t
  use voussoir_assembly, only: assembly_t
  use voussoir_model, only: model_t
  use voussoir_simulation, only: run_result_t
  use voussoir_setup, only: run_config
  use voussoir_sweep_output, only: sweep_table_t, dt_check_table, table_row, table_set, table_append, table_value
  use voussoir_sweep_plan, only: sweep_plan_t
  use voussoir_sweep_jobs, only: job_run_config
  implicit none
  private

  public :: check_time_step

contains

  !> Time-step check of an IDA (rank 0, after the searches): the runs at scale_stood and
  !> at scale_threshold of `dt_check_rows` rows (spread over the rows that collapsed by
  !> the golden-ratio sequence, so that they mix records and samples whatever the
  !> numbers of each) are redone at half the time step; an outcome that changes says
  !> the threshold depends on the step.
  subroutine check_time_step(plan, results, dt_check, n_pick, n_changed, status)
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_table_t), intent(in) :: results         !! the IDA rows
    type(sweep_table_t), intent(out) :: dt_check       !! the runs redone
    integer, intent(out) :: n_pick, n_changed          !! rows checked, outcomes changed
    type(status_t), intent(inout) :: status
    integer, allocatable :: rows(:), picked(:)
    integer :: k, r, job, side
    real(dp) :: scale
    real(dp), allocatable :: row(:)
    type(config_t) :: cfg
    type(assembly_t) :: assembly
    type(model_t) :: model
    type(run_result_t) :: res
    character(len=*), parameter :: sides(2) = ['scale_stood    ', 'scale_threshold']

    dt_check = dt_check_table()
    rows = pack([(r, r = 1, results%n_rows)], [(nint(table_value(results, 'censored', r)) == 0 .and. &
                                                  nint(table_value(results, 'failed', r)) == 0, &
                                                  r = 1, results%n_rows)])
    n_changed = 0
    n_pick = min(plan%dt_check_rows, size(rows))
    allocate (picked(0))
    k = 0
    do while (size(picked) < n_pick)
      k = k + 1
      r = rows(1 + int(modulo(k*0.6180339887498949_dp, 1.0_dp)*size(rows)))
      if (.not. any(picked == r)) picked = [picked, r]
    end do
    do k = 1, n_pick
      r = picked(k)
      job = nint(table_value(results, 'job', r))
      do side = 1, 2
        scale = table_value(results, trim(sides(side)), r)
        if (.not. scale > 0.0_dp) cycle
        cfg = job_run_config(plan, job, scale)
        cfg%solver%dt_s = 0.5_dp*cfg%solver%dt_s
        call run_config(cfg, assembly, model, res, status)
        if (.not. status%ok) then
          status%message = 'dt/2 check of job '//itoa(job)//': '//trim(status%message)
          return
        end if
        call table_row(dt_check, row)
        call table_set(dt_check, row, 'job', real(job, dp))
        call table_set(dt_check, row, 'scale', scale)
        call table_set(dt_check, row, 'collapsed', merge(1.0_dp, 0.0_dp, side == 2))
        call table_set(dt_check, row, 'collapsed_half_dt', merge(1.0_dp, 0.0_dp, res%collapsed))
        call table_append(dt_check, row)
        if (res%collapsed .neqv. side == 2) n_changed = n_changed + 1
      end do
    end do
  end subroutine check_time_step

end module voussoir_sweep_dt_check
