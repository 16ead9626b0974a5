!> ESM/ITACA ASCII records (src/motion/esm_record.f90, through read_ground_record): files
!> written here in the format's layout (a header of `KEY: value` lines, then one sample
!> a line) are read in the unit their UNITS names; a file without a unit, or with one
!> that is not an acceleration's, is refused with a message that says how to state it.
program test_esm_record
  use voussoir_kinds, only: dp, g_m_s2
  use voussoir_status, only: status_t
  use voussoir_ground_record, only: ground_record_t, read_ground_record
  use voussoir_assert, only: assert_true, assert_close, assert_summary
  implicit none

  real(dp), parameter :: samples(5) = [0.0_dp, 12.5_dp, -31.25_dp, 7.0_dp, -0.5_dp]
  type(ground_record_t) :: rec
  type(status_t) :: status
  integer :: k

  ! cm/s^2 (as ESM and ITACA write it): samples / 100 in m/s2.
  call write_esm('esm_cm.ASC', 'UNITS: cm/s^2')
  call read_ground_record('esm_cm.ASC', rec, status)
  call assert_true(status%ok, 'cm/s^2 file read: '//trim(status%message))
  if (status%ok) then
    call assert_true(size(rec%accel_m_s2) == 5, 'cm/s^2: NDATA samples')
    call assert_close(rec%dt_s, 0.005_dp, 'cm/s^2: SAMPLING_INTERVAL_S', rtol=1.0e-15_dp)
    do k = 1, 5
      call assert_close(rec%accel_m_s2(k), samples(k)/100.0_dp, 'cm/s^2: sample in m/s2', rtol=1.0e-15_dp, &
                        atol=1.0e-300_dp)
    end do
    call assert_true(index(rec%description, 'TEST_EVENT') > 0 .and. index(rec%description, 'AMT') > 0, &
                     'description names the event and the station: '//trim(rec%description))
    call assert_true(rec%name == 'esm_cm', 'name is the file name without extension')
  end if

  ! m/s^2 and g, in any spelling the table knows.
  call write_esm('esm_m.asc', 'UNITS: m/s^2')
  call read_ground_record('esm_m.asc', rec, status)
  call assert_true(status%ok, 'm/s^2 file read')
  if (status%ok) call assert_close(rec%accel_m_s2(3), -31.25_dp, 'm/s^2: sample as written', rtol=1.0e-15_dp)
  call write_esm('esm_g.asc', 'UNITS: g')
  call read_ground_record('esm_g.asc', rec, status)
  call assert_true(status%ok, 'g file read')
  if (status%ok) call assert_close(rec%accel_m_s2(2), 12.5_dp*g_m_s2, 'g: sample times g', rtol=1.0e-15_dp)

  ! Refused: no UNITS (the message says how to state it), a blank one, a velocity unit,
  ! a velocity record.
  call refused('esm_none.asc', 'USER5:', "UNITS: cm/s^2", 'no UNITS line')
  call refused('esm_blank.asc', 'UNITS:', "UNITS: cm/s^2", 'a blank UNITS')
  call refused('esm_velocity_unit.asc', 'UNITS: cm/s', "UNITS = 'cm/s'", 'a unit of velocity')
  call refused('esm_velocity.asc', 'DATA_TYPE: VELOCITY', 'ACCELERATION', 'a velocity record')
  call remove([character(len=32) :: 'esm_cm.ASC', 'esm_m.asc', 'esm_g.asc', 'esm_none.asc', 'esm_blank.asc', &
                'esm_velocity_unit.asc', 'esm_velocity.asc'])
  call assert_summary()

contains

  !> An ESM file of the five samples, its header's UNITS line replaced by `units_line`.
  subroutine write_esm(path, units_line)
    character(len=*), intent(in) :: path, units_line
    integer :: unit
    open (newunit=unit, file=path, status='replace', action='write')
    write (unit, '(a)') 'EVENT_NAME: TEST_EVENT', 'EVENT_ID: EMSC-20160824_0000006', &
      'EVENT_DATE_YYYYMMDD: 20160824', 'EVENT_TIME_HHMMSS: 013632', 'EVENT_LATITUDE_DEGREE: 42.6983', &
      'EVENT_LONGITUDE_DEGREE: 13.2335', 'EVENT_DEPTH_KM: 8.1', 'HYPOCENTER_REFERENCE: INGV', &
      'MAGNITUDE_W: 6.0', 'NETWORK: IT', 'STATION_CODE: AMT', 'STATION_NAME: AMATRICE', 'STREAM: HNE', &
      'DATE_TIME_FIRST_SAMPLE_YYYYMMDD_HHMMSS: 20160824_013632.000', 'SAMPLING_INTERVAL_S: 0.005000', &
      'NDATA: 5', 'DURATION_S: 0.025', 'DATA_TYPE: ACCELERATION', trim(units_line), &
      'INSTRUMENT: sensor = Unknown [Unknown] | digitizer = Unknown [Unknown]', &
      'BASELINE_CORRECTION: BASELINE REMOVED', 'FILTER_TYPE: BUTTERWORTH', 'FILTER_ORDER: 2', &
      'LOW_CUT_FREQUENCY_HZ: 0.100', 'HIGH_CUT_FREQUENCY_HZ: 30.000', 'USER1:', 'USER2:', 'USER3:', 'USER4:'
    write (unit, '(es14.6)') samples
    close (unit)
  end subroutine write_esm

  !> Delete the files this test wrote.
  subroutine remove(paths)
    character(len=*), intent(in) :: paths(:)
    integer :: unit, k
    do k = 1, size(paths)
      open (newunit=unit, file=trim(paths(k)), status='old')
      close (unit, status='delete')
    end do
  end subroutine remove

  !> The file with `units_line` is refused with a message holding `words`.
  subroutine refused(path, units_line, words, label)
    character(len=*), intent(in) :: path, units_line, words, label
    type(status_t) :: st
    call write_esm(path, units_line)
    call read_ground_record(path, rec, st)
    call assert_true(.not. st%ok .and. index(st%message, words) > 0 .and. index(st%message, path) > 0, &
                     label//' refused: '//trim(st%message))
  end subroutine refused

end program test_esm_record
