!> The parts of a sweep plan that belong to an incremental dynamic analysis (`&sweep
!> mode = 'ida'`): the records and their intensity measures, and the model samples
!> drawn by a seeded Latin hypercube from uniform distributions between bounds (or read
!> from a file: src/sweep/model_samples.f90; both make a sample's case by `sample_case`).
!>
!> Sampled variables (each sampled when its `&sweep` range is given, in this order):
!> friction (`friction_range`), contact inset (`contact_inset_range_m`), ring thickness
!> (`thickness_range_m`) and voussoir-size imperfection (`size_imperfection_range`: the
!> amplitude of a random variation of the voussoirs' angles, see
!> voussoir_assembly's `voussoir_angle_factors`; sample s gets the pattern of seed
!> `sample_seed + s`).
module voussoir_sweep_ida
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa
  use voussoir_config, only: config_t, validate_config, resolve_path, fmt_real, arch_rule, arch_rule_text, &
                             waveform_afd, waveform_accelerogram
  use voussoir_ground_record, only: ground_record_t, record_intensity_t, read_ground_record, record_intensity
  use voussoir_latin_hypercube, only: latin_hypercube
  use voussoir_input_range, only: need
  use voussoir_record_set, only: record_set_t, read_record_set
  implicit none
  private

  public :: n_sampled, sampled_names, range_names, ida_records_t, read_ida_records, read_set_records, sample_sets
  public :: sample_variables, sample_case, set_record_polarity, record_label, check_base_motion

  !> &sweep record_polarity: each record as recorded, reversed (its horizontal sign
  !> flipped: the motion mirrored), or both, the reversed one a row of its own after it.
  character(len=*), parameter, public :: polarity_forward = 'forward', polarity_reversed = 'reversed', &
    polarity_both = 'both'
  character(len=16), parameter, public :: polarity_names(3) = [character(len=16) :: &
    polarity_forward, polarity_reversed, polarity_both]
  !> What a reversed record's name is followed by in the tables.
  character(len=*), parameter :: reversed_suffix = ' (reversed)'

  integer, parameter :: n_sampled = 4                 !! variables that can be sampled
  !> The &arch variables a model sample can set: those of the Latin hypercube, and the
  !> extrados radius, which a file of samples may give (src/sweep/model_samples.f90).
  character(len=24), parameter :: sample_variables(5) = [character(len=24) :: &
    'friction', 'contact_inset_m', 'thickness_m', 'r_ext_m', 'size_imperfection']
  character(len=24), parameter :: sampled_names(n_sampled) = [character(len=24) :: &
    'friction', 'contact_inset_m', 'thickness_m', 'size_imperfection']
  character(len=24), parameter :: range_names(n_sampled) = [character(len=24) :: &
    'friction_range', 'contact_inset_range_m', 'thickness_range_m', 'size_imperfection_range']

  !> The records of an IDA and what the plan needs of each.
  type :: ida_records_t
    integer :: n = 0
    character(len=512), allocatable :: files(:)     !! as resolved (relative to the input's folder)
    character(len=512), allocatable :: given(:)     !! as written in record_files; of a set, the record's name
    real(dp), allocatable :: pga_m_s2(:), pgv_m_s(:), duration_s(:)  !! of the record's own samples (unscaled)
    !> Of a packaged set (record_set): each record's earthquake and year, moment magnitude
    !> and closest distance to the rupture; '' and NaN for files of record_files.
    character(len=512), allocatable :: events(:)
    real(dp), allocatable :: magnitude(:), distance_km(:)
    !> Of a packaged set too: the site's Vs30 [m/s], the pulse classification (1, 0, NaN
    !> not classified) and the pulse period [s] (NaN without a pulse); NaN for record_files.
    real(dp), allocatable :: vs30_m_s(:), pulse(:), pulse_period_s(:)
    integer, allocatable :: polarity(:)             !! &motion record_polarity of each: 1, or -1 reversed
  end type ida_records_t

contains

  !> Read every record of `given` (names relative to the folder of `path`), refusing a
  !> bad one with its file and line.
  subroutine read_ida_records(path, given, records, status)
    character(len=*), intent(in) :: path
    character(len=*), intent(in) :: given(:)
    type(ida_records_t), intent(out) :: records
    type(status_t), intent(inout) :: status
    integer :: k
    records%n = size(given)
    allocate (records%files(records%n), records%given(records%n), records%pga_m_s2(records%n), &
              records%pgv_m_s(records%n), records%duration_s(records%n), records%events(records%n), &
              records%magnitude(records%n), records%distance_km(records%n), records%vs30_m_s(records%n), &
              records%pulse(records%n), records%pulse_period_s(records%n))
    records%events = ''
    records%magnitude = ieee_value(1.0_dp, ieee_quiet_nan)
    records%distance_km = records%magnitude
    records%vs30_m_s = records%magnitude
    records%pulse = records%magnitude
    records%pulse_period_s = records%magnitude
    do k = 1, records%n
      records%given(k) = given(k)
      records%files(k) = resolve_path(path, given(k))
    end do
    call read_records(path, 'record_files', records, status)
  end subroutine read_ida_records

  !> The records of the packaged set `name` (`components`: 'both' or 'first' of each
  !> pair), with their metadata; see src/sweep/record_set.f90.
  subroutine read_set_records(path, name, components, records, status)
    character(len=*), intent(in) :: path, name, components
    type(ida_records_t), intent(out) :: records
    type(status_t), intent(inout) :: status
    type(record_set_t) :: set
    call read_record_set(path, name, components, set, status)
    if (.not. status%ok) return
    records%n = set%n
    records%files = set%files
    records%given = set%names
    records%events = set%events
    records%magnitude = set%magnitude
    records%distance_km = set%distance_km
    records%vs30_m_s = set%vs30_m_s
    records%pulse = set%pulse
    records%pulse_period_s = set%pulse_period_s
    allocate (records%pga_m_s2(set%n), records%pgv_m_s(set%n), records%duration_s(set%n))
    call read_records(path, "record_set = '"//trim(name)//"' record", records, status)
  end subroutine read_set_records

  !> Read each record file of `records` and its intensity measures, refusing a bad one
  !> with its file and line (`what`: how the input named them, for the message).
  subroutine read_records(path, what, records, status)
    character(len=*), intent(in) :: path, what
    type(ida_records_t), intent(inout) :: records
    type(status_t), intent(inout) :: status
    type(ground_record_t) :: rec
    type(record_intensity_t) :: im
    integer :: k
    records%polarity = [(1, k = 1, records%n)]
    do k = 1, records%n
      call read_ground_record(trim(records%files(k)), rec, status)
      if (.not. status%ok) then
        status%message = path//': &sweep '//what//'('//itoa(k)//'): '//trim(status%message)
        return
      end if
      im = record_intensity(rec%accel_m_s2, rec%dt_s)
      if (.not. im%pga_m_s2 > 0.0_dp) then
        call fail(status, path//': &sweep '//what//'('//itoa(k)//') = '//trim(records%given(k))// &
                  ': the record is all zeros (no scale can make it shake)')
        return
      end if
      records%pga_m_s2(k) = im%pga_m_s2
      records%pgv_m_s(k) = im%pgv_m_s
      records%duration_s(k) = (size(rec%accel_m_s2) - 1)*rec%dt_s
    end do
  end subroutine read_records

  !> The base case's &motion as an IDA can play it: a waveform the records replace, no
  !> vertical record file (the records have none: vertical_ratio gives the vertical) and
  !> no polarity of its own (&sweep record_polarity chooses it).
  subroutine check_base_motion(path, mode, base, status)
    character(len=*), intent(in) :: path, mode   !! mode: 'ida' or 'msa' (with its quotes), for messages
    type(config_t), intent(in) :: base
    type(status_t), intent(inout) :: status
    if (base%motion%waveform /= waveform_afd .and. base%motion%waveform /= waveform_accelerogram) then
      call fail(status, path//": &motion waveform = '"//trim(base%motion%waveform)//"': mode = "//mode//' '// &
                'drives the table with each record of &sweep record_files; leave waveform unset')
      return
    end if
    if (len_trim(base%motion%record_vertical_file) > 0) then
      call fail(status, path//": &motion record_vertical_file = '"//trim(base%motion%record_vertical_file)// &
                "': mode = "//mode//" plays records without vertical files; give the vertical component as "// &
                '&motion vertical_ratio (vertical / horizontal acceleration, scaled with the record)')
      return
    end if
    if (base%motion%record_polarity /= 1) then
      call fail(status, path//": &motion record_polarity = -1: mode = "//mode//" chooses the records' polarity "// &
                "with &sweep record_polarity ('forward', 'reversed' or 'both')")
      return
    end if
  end subroutine check_base_motion

  !> Play the records as `choice` says (one of polarity_names): forward, reversed, or
  !> both (record k forward, then reversed: the intensity measures are those of |a|).
  subroutine set_record_polarity(records, choice)
    type(ida_records_t), intent(inout) :: records
    character(len=*), intent(in) :: choice
    integer, allocatable :: twice(:)
    integer :: k
    select case (choice)
    case (polarity_reversed)
      records%polarity = -records%polarity
    case (polarity_both)
      twice = [((k + 1)/2, k = 1, 2*records%n)]
      records%files = records%files(twice)
      records%given = records%given(twice)
      records%pga_m_s2 = records%pga_m_s2(twice)
      records%pgv_m_s = records%pgv_m_s(twice)
      records%duration_s = records%duration_s(twice)
      records%events = records%events(twice)
      records%magnitude = records%magnitude(twice)
      records%distance_km = records%distance_km(twice)
      records%vs30_m_s = records%vs30_m_s(twice)
      records%pulse = records%pulse(twice)
      records%pulse_period_s = records%pulse_period_s(twice)
      records%polarity = [(merge(1, -1, modulo(k, 2) == 1), k = 1, 2*records%n)]
      records%n = 2*records%n
    end select
  end subroutine set_record_polarity

  !> Record `k` as the tables name it: as given, followed by ' (reversed)' when reversed.
  pure function record_label(records, k) result(label)
    type(ida_records_t), intent(in) :: records
    integer, intent(in) :: k
    character(len=:), allocatable :: label
    label = trim(records%given(k))
    if (records%polarity(k) == -1) label = label//reversed_suffix
  end function record_label

  !> `n_samples` model samples of the base case: for every variable whose range
  !> (`ranges(:, v)`, low and high; unset where `given(v)` is false) is given, a Latin
  !> hypercube draw between the bounds. `names` and `values(n_params, n_samples)` are the
  !> sampled variables; `set_cfg(0:n_samples-1)` the validated case of each sample.
  subroutine sample_sets(path, base, n_samples, seed, ranges, given, names, values, set_cfg, status)
    character(len=*), intent(in) :: path
    type(config_t), intent(in) :: base
    integer, intent(in) :: n_samples, seed
    real(dp), intent(in) :: ranges(2, n_sampled)
    logical, intent(in) :: given(n_sampled)
    character(len=24), allocatable, intent(out) :: names(:)
    real(dp), allocatable, intent(out) :: values(:, :)
    type(config_t), allocatable, intent(out) :: set_cfg(:)
    type(status_t), intent(inout) :: status
    real(dp), allocatable :: u(:, :)
    type(status_t) :: check
    integer :: v, p, s

    do v = 1, n_sampled
      if (.not. given(v)) cycle
      if (.not. (ranges(1, v) <= ranges(2, v))) then
        call fail(status, path//': &sweep '//trim(range_names(v))//' = '//fmt_real(ranges(1, v))//', '// &
                  fmt_real(ranges(2, v))//': the low bound must not exceed the high one')
        return
      end if
      do p = 1, 2
        call need(arch_rule(sampled_names(v), ranges(p, v)), path, 'sweep', trim(range_names(v))//'('//itoa(p)//')', &
                  ranges(p, v), arch_rule_text(sampled_names(v)), status)
      end do
      if (.not. status%ok) return
    end do
    names = pack(sampled_names, given)
    allocate (values(size(names), n_samples), set_cfg(0:n_samples - 1))
    u = latin_hypercube(n_samples, size(names), seed)
    do s = 0, n_samples - 1
      p = 0
      do v = 1, n_sampled
        if (.not. given(v)) cycle
        p = p + 1
        values(p, s + 1) = ranges(1, v) + u(p, s + 1)*(ranges(2, v) - ranges(1, v))
      end do
      set_cfg(s) = sample_case(base, names, values(:, s + 1), seed + s)
      call validate_config(set_cfg(s), check)
      if (.not. check%ok) then
        call fail(status, path//': &sweep model sample '//itoa(s)//': '//trim(check%message))
        return
      end if
    end do
  end subroutine sample_sets

  !> The base case with the values `values` of the &arch variables `names` (among
  !> `sample_variables`); a size imperfection gets the pattern of seed `pattern_seed`.
  pure function sample_case(base, names, values, pattern_seed) result(cfg)
    type(config_t), intent(in) :: base
    character(len=*), intent(in) :: names(:)
    real(dp), intent(in) :: values(:)
    integer, intent(in) :: pattern_seed
    type(config_t) :: cfg
    integer :: p
    cfg = base
    do p = 1, size(names)
      select case (names(p))
      case ('friction')
        cfg%arch%friction = values(p)
      case ('contact_inset_m')
        cfg%arch%contact_inset_m = values(p)
      case ('thickness_m')
        cfg%arch%thickness_m = values(p)
      case ('r_ext_m')
        cfg%arch%r_ext_m = values(p)
      case ('size_imperfection')
        cfg%arch%size_imperfection = values(p)
        cfg%arch%imperfection_seed = pattern_seed
      end select
    end do
  end function sample_case

end module voussoir_sweep_ida
