# Regression cases of uhpc-macro (uhpc_regression_case / uhpc_bad_input_case).

# --- the shipped small case end to end: rigid sphere into an elastic block ---
uhpc_regression_case(NAME macro_elastic_block OUTPUT result.json
  COMMAND $<TARGET_FILE:uhpc-macro> -q --config data/macro_elastic_block.json)

# --- bad input: exit 2, one line naming file, key and reason ---
set(_macro $<TARGET_FILE:uhpc-macro>)
set(_macro_case --config data/macro_elastic_block.json --out ${UHPC_REGRESSION_OUT}/bad)
uhpc_bad_input_case(NAME macro_misspelt_key
  STDERR "error: data/macro_elastic_block.json: key 'projectile.velocty_m_s': unknown key (did you mean 'velocity_m_s'?)"
  COMMAND ${_macro} ${_macro_case} --set projectile.velocty_m_s=800)
uhpc_bad_input_case(NAME macro_negative_mass
  STDERR "error: data/macro_elastic_block.json: key 'projectile.mass_kg': value -1 is out of range, must be > 0"
  COMMAND ${_macro} ${_macro_case} --set projectile.mass_kg=-1)
uhpc_bad_input_case(NAME macro_unknown_material
  STDERR "error: data/macro_elastic_block.json: key 'material.model': value 'foo' is not one of: elastic, j2, afc"
  COMMAND ${_macro} ${_macro_case} --set material.model=foo)
uhpc_bad_input_case(NAME macro_j2_needs_yield_stress
  STDERR "error: data/macro_elastic_block.json: key 'material.yield_stress_Pa': required key is missing"
  COMMAND ${_macro} ${_macro_case} --set material.model=j2)
uhpc_bad_input_case(NAME macro_bad_sdel_handoff
  STDERR "error: tests/regression/sdel_paper/bad_format.json: key 'format': expected \"uhpc-sdel/1\", got \"uhpc-sdel/0\""
  COMMAND ${_macro} ${_macro_case} --sdel tests/regression/sdel_paper/bad_format.json)
uhpc_bad_input_case(NAME macro_unknown_rim_support
  STDERR "error: data/macro_elastic_block.json: key 'support.rim': value 'clamped' is not one of: free, fixed"
  COMMAND ${_macro} ${_macro_case} --set support.rim=clamped)
uhpc_bad_input_case(NAME macro_sphere_larger_than_target
  STDERR "error: data/macro_elastic_block.json: key 'projectile.radius_m': the sphere must be smaller than the target's half width"
  COMMAND ${_macro} ${_macro_case} --set projectile.radius_m=0.03)
uhpc_bad_input_case(NAME macro_disc_without_radius
  STDERR "error: data/macro_elastic_block.json: key 'target.radius_m': required key is missing"
  COMMAND ${_macro} ${_macro_case} --set target.shape=disc)
uhpc_bad_input_case(NAME macro_zero_output_interval
  STDERR "error: data/macro_elastic_block.json: key 'run.output_interval_steps': value 0 is out of range, must be >= 1"
  COMMAND ${_macro} ${_macro_case} --set run.output_interval_steps=0)
uhpc_bad_input_case(NAME macro_missing_out
  STDERR "error: --out is required"
  COMMAND ${_macro} --config data/macro_elastic_block.json)
uhpc_bad_input_case(NAME macro_afc_needs_constants_file
  STDERR "error: data/macro_elastic_block.json: key 'material.constants_file': required key is missing"
  COMMAND ${_macro} ${_macro_case} --set material.model=afc)
