/* The one GLPK call Fortran cannot make directly: glp_simplex takes a glp_smcp struct
 * whose layout belongs to the GLPK version, so it is filled here (voussoir_glpk binds
 * the rest of the C API with iso_c_binding). Silent, scaled, presolved when asked (voussoir_glpk does not ask: see there). */
#include <glpk.h>

int voussoir_glpk_simplex(glp_prob *lp, int presolve)
{
  glp_smcp parm;
  glp_term_out(GLP_OFF);
  glp_scale_prob(lp, GLP_SF_AUTO);
  glp_init_smcp(&parm);
  parm.msg_lev = GLP_MSG_OFF;
  parm.presolve = presolve ? GLP_ON : GLP_OFF;
  return glp_simplex(lp, &parm);
}
