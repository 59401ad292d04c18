//! Layer 4: pure functions of fields: error measures against reference solutions, ...

pub mod hertz_error;
pub mod limit_diagram;
pub mod stress_field;
pub mod woehler;
