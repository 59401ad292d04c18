//! Error measures of a computed pressure against a reference, the paper's (17).
