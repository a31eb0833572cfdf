//! TTF and OTF export.
