!> What voussoir-limit prints of the load cases of &load_cases: each case's LP table and
!> a summary of all (the load factor on the factored live loads, the adequacy factor of
!> an assessment), and their keys of the JSON object (docs/results_format.md).
module voussoir_limit_case_output
  use voussoir_kinds, only: dp
  use voussoir_text, only: itoa, fmt_json_real, json_string, fmt_significant
  use voussoir_limit_load_cases, only: case_study_t, governing_case
  use voussoir_limit_lp_output, only: write_lp_table, curve_json
  implicit none
  private
  public :: write_cases_table, cases_json

contains

  !> Each case's LP table, then the summary: per case its factors, its factored live load,
  !> both load factors, the critical position, the collapse live load and the verdict.
  subroutine write_cases_table(u, cases, friction)
    integer, intent(in) :: u
    type(case_study_t), intent(in) :: cases(:)
    real(dp), intent(in) :: friction
    integer :: k, gov
    character(len=:), allocatable :: row
    do k = 1, size(cases)
      write (u, '(/,a)') 'Load case '//itoa(k)//" '"//trim(cases(k)%name)//"': gamma_Q "// &
        fmt_significant(cases(k)%gamma_q, 6)//' on its live loads, gamma_G '//fmt_significant(cases(k)%gamma_g, 6)// &
        ' on every permanent load'
      call write_lp_table(u, cases(k)%lp, friction)
    end do
    gov = governing_case(cases)
    write (u, '(/,a)') 'Load cases: lambda is the multiple of the factored live loads that brings the assembly down, '// &
      'the factored permanent loads held fixed (the adequacy factor: >= 1, the factored loads are carried)'
    write (u, '(a)') '  case  name                          gamma_Q  gamma_G   live load [kN]  lambda (assoc.)  '// &
      'lambda (non-assoc.)  critical x [m]  collapse live load [kN]'
    do k = 1, size(cases)
      associate (lp => cases(k)%lp)
        row = '  '//pad(itoa(k), 6)//pad(trim(cases(k)%name), 30)//pad(fmt_significant(cases(k)%gamma_q, 4), 9)// &
          pad(fmt_significant(cases(k)%gamma_g, 4), 10)//pad(fmt_significant(1.0e-3_dp*cases(k)%live_total_n, 6), 16)
        row = row//pad(fmt_significant(lp%assoc%load_factor, 6), 17)
        if (lp%nonassociative_solved) then
          row = row//pad(fmt_significant(lp%nonassoc%load_factor, 6), 21)
        else
          row = row//pad('none', 21)
        end if
        if (lp%has_path) then
          row = row//pad(fmt_significant(lp%critical_x_m, 6), 16)
        else
          row = row//pad('(no path)', 16)
        end if
        row = row//fmt_significant(1.0e-3_dp*lp%assoc%load_factor*cases(k)%live_total_n, 6)// &
          trim(merge('  adequate    ', '  NOT adequate', lp%assoc%load_factor >= 1.0_dp))
        if (k == gov) row = row//'  (governs)'
        write (u, '(a)') row
      end associate
    end do
  end subroutine write_cases_table

  !> The "load_cases" list and "governing_load_case" (from 1; null without cases), each
  !> line ending with a comma.
  function cases_json(cases) result(text)
    type(case_study_t), intent(in) :: cases(:)
    character(len=:), allocatable :: text
    character(len=1), parameter :: nl = achar(10)
    integer :: k, gov
    text = '  "load_cases": ['
    do k = 1, size(cases)
      associate (lp => cases(k)%lp)
        if (k > 1) text = text//','
        text = text//nl//'    {"name": '//json_string(trim(cases(k)%name))//', "gamma_q": '// &
          fmt_json_real(cases(k)%gamma_q)//', "gamma_g": '//fmt_json_real(cases(k)%gamma_g)//','//nl// &
          '     "live_load": '//json_string(lp%live_load)//','//nl// &
          '     "factored_live_load_n": '//fmt_json_real(cases(k)%live_total_n)//', "load_factor": '// &
          fmt_json_real(lp%assoc%load_factor)//', "adequacy_factor": '//fmt_json_real(lp%assoc%load_factor)// &
          ', "characteristic_load_factor": '//fmt_json_real(lp%assoc%load_factor*cases(k)%gamma_q)// &
          ', "collapse_live_load_n": '//fmt_json_real(lp%assoc%load_factor*cases(k)%live_total_n)// &
          ', "load_factor_nonassociative": '
        if (lp%nonassociative_solved) then
          text = text//fmt_json_real(lp%nonassoc%load_factor)
        else
          text = text//'null'
        end if
        text = text//','//nl//'     "critical_position": '
        if (lp%has_path) then
          text = text//'{"x_m": '//fmt_json_real(lp%critical_x_m)//', "load_factor": '// &
                 fmt_json_real(lp%critical_load_factor)//'}'
        else
          text = text//'null'
        end if
        text = text//','//nl//'     "load_factor_curve": '//curve_json(lp)//'}'
      end associate
    end do
    text = text//'],'//nl
    gov = governing_case(cases)
    if (gov > 0) then
      text = text//'  "governing_load_case": '//itoa(gov)//','//nl
    else
      text = text//'  "governing_load_case": null,'//nl
    end if
  end function cases_json

  !> `text` padded with blanks to `width` (at least one blank after it).
  pure function pad(text, width) result(out)
    character(len=*), intent(in) :: text
    integer, intent(in) :: width
    character(len=max(width, len(text) + 1)) :: out
    out = text
  end function pad

end module voussoir_limit_case_output
