//! Collision filtering with Box2D's semantics (`b2Filter`, `b2ShouldShapesCollide`).
//!
//! Every shape carries a [`Filter`]: the categories it belongs to (a bit
//! set), the categories it accepts (a mask) and a group index. Two shapes
//! are considered for contact when
//!
//! - they share a **non-zero group**: a positive group always collides, a
//!   negative group never does (a ragdoll's bones), whatever the bits; else
//! - each one's category meets the other's mask:
//!   `(a.category & b.mask) != 0 && (b.category & a.mask) != 0`.
//!
//! World queries take a [`QueryFilter`]: a shape is reported when its
//! category meets the query's mask and the query's category meets its mask
//! (Box2D's `b2QueryFilter`).

/// Which shapes a shape collides with. The default collides with
/// everything: category bit 1, every mask bit, group 0.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Filter {
    /// The categories this shape belongs to (usually one bit).
    pub category: u64,
    /// The categories this shape accepts contacts with.
    pub mask: u64,
    /// Shapes with the same non-zero group always collide (positive) or
    /// never collide (negative), overriding category and mask; 0 means no
    /// group.
    pub group: i64,
}

impl Default for Filter {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl Filter {
    /// Category 1, every mask bit, no group (Box2D's `b2DefaultFilter`).
    pub const DEFAULT: Self = Self {
        category: 1,
        mask: u64::MAX,
        group: 0,
    };

    /// Whether shapes with filters `self` and `other` may collide.
    pub fn should_collide(&self, other: &Filter) -> bool {
        if self.group == other.group && self.group != 0 {
            return self.group > 0;
        }
        (self.category & other.mask) != 0 && (other.category & self.mask) != 0
    }
}

/// Which shapes a world query reports (Box2D's `b2QueryFilter`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct QueryFilter {
    /// The categories the query belongs to.
    pub category: u64,
    /// The categories the query accepts.
    pub mask: u64,
}

impl Default for QueryFilter {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl QueryFilter {
    /// Every category, every mask bit.
    pub const DEFAULT: Self = Self {
        category: u64::MAX,
        mask: u64::MAX,
    };

    /// Whether a shape with filter `shape` is reported by this query.
    pub fn accepts(&self, shape: &Filter) -> bool {
        (shape.category & self.mask) != 0 && (self.category & shape.mask) != 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_filters_collide() {
        assert!(Filter::DEFAULT.should_collide(&Filter::DEFAULT));
    }

    #[test]
    fn groups_override_bits() {
        let never = Filter {
            group: -3,
            ..Filter::DEFAULT
        };
        assert!(!never.should_collide(&never));
        let always = Filter {
            category: 2,
            mask: 0,
            group: 5,
        };
        assert!(always.should_collide(&always));
        // Different groups fall back to the bits.
        let other = Filter {
            group: 4,
            ..Filter::DEFAULT
        };
        assert!(!always.should_collide(&other));
    }

    #[test]
    fn category_must_meet_both_masks() {
        let player = Filter {
            category: 0b01,
            mask: 0b10,
            group: 0,
        };
        let enemy = Filter {
            category: 0b10,
            mask: 0b01,
            group: 0,
        };
        let ghost = Filter {
            category: 0b100,
            mask: 0b01,
            group: 0,
        };
        assert!(player.should_collide(&enemy));
        assert!(!player.should_collide(&ghost));
        assert!(!player.should_collide(&player));
    }

    #[test]
    fn query_filter_checks_both_ways() {
        let q = QueryFilter {
            category: 1,
            mask: 0b10,
        };
        assert!(q.accepts(&Filter {
            category: 0b10,
            mask: 1,
            group: 0
        }));
        assert!(!q.accepts(&Filter {
            category: 0b10,
            mask: 0b100,
            group: 0
        }));
        assert!(!q.accepts(&Filter::DEFAULT));
    }
}
