//! The `prep` (control value program) table: smart dropout control for the unhinted
//! TrueType outlines.
//!
//! Without hinting, a rasterizer at small sizes can drop thin stems and joins entirely
//! ("dropouts"). The program below turns on the rasterizer's dropout control at every size
//! with the "smart" rules, which is what fontmake/gftools add to unhinted fonts. Written as
//! bytes by hand: it is seven bytes, and no maintained Rust crate assembles TrueType
//! instructions.

/// The program, one instruction per line:
pub const SMART_DROPOUT_CONTROL: [u8; 7] = [
    // PUSHW[0] 511: push one word. 511 = 0x01FF: bit 8 (0x100) switches dropout control on
    // when the ppem is at most the threshold in bits 0-7, and threshold 0xFF means every
    // size; bit 9 (0x200) left clear keeps it on for rotated glyphs, bit 10 for stretched.
    0xB8, 0x01, 0xFF, // SCANCTRL: pop the flags above into the scan control state.
    0x85,
    // PUSHB[0] 4: push one byte, scan type 4 = smart dropout control including stubs
    // (rules 1, 2 and 3).
    0xB0, 0x04, // SCANTYPE: pop it into the scan type state.
    0x8D,
];

/// Stack depth the program needs, for `maxp.maxStackElements`.
pub const STACK_DEPTH: u16 = 1;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn push_scanctrl_push_scantype() {
        // Decode: each push is followed by its consumer, so the stack never holds more
        // than one value, and the values are the documented ones.
        let p = SMART_DROPOUT_CONTROL;
        assert_eq!(p[0], 0xB8, "PUSHW[0] (one word)");
        assert_eq!(u16::from_be_bytes([p[1], p[2]]), 511);
        assert_eq!(p[3], 0x85, "SCANCTRL");
        assert_eq!((p[4], p[5]), (0xB0, 4), "PUSHB[0] 4");
        assert_eq!(p[6], 0x8D, "SCANTYPE");
        assert_eq!(STACK_DEPTH, 1);
    }
}
