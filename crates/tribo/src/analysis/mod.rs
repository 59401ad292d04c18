//! Layer 4: pure functions of fields: error measures against reference solutions, the
//! stress field, volume damageability and the energy criterion.

pub mod bem_field;
pub mod damage;
pub mod edge_refinement;
pub mod energy_criterion;
pub mod hertz_error;
pub mod limit_diagram;
pub mod periodic_field;
pub mod stress_field;
pub mod surface_response;
pub mod woehler;
