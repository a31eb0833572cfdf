//! Helpers shared by the test modules.

pub mod cli;
pub mod corpus;
pub mod curves;
pub mod paths;
pub mod tree;
