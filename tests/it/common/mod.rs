//! Helpers shared by the test modules.

pub mod cli;
pub mod corpus;
pub mod curves;
pub mod fonts;
pub mod masters;
pub mod paths;
pub mod temp;
pub mod tools;
pub mod tree;
