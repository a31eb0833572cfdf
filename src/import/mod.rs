//! Importers: existing outlines -> X-spline sources.
