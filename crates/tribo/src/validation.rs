//! The verification suite: every analytic comparison the tests make, as table rows.
