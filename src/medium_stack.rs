//! Nested media (Schmidt & Budge 2002, "Simple Nested Dielectrics in Ray Traced Images"):
//! each path carries the stack of volumetric dielectrics it is inside, so a ray crossing
//! from one medium directly into another (water in a glass, a gem set in resin) refracts
//! with the ratio of the two indices, not medium/air.
//!
//! Invariants: the stack holds the volumetric materials (KHR_materials_volume thickness > 0)
//! the path is inside, with their priorities, in the order they were entered. Where volumes
//! overlap, the medium the path is in is the one of **highest priority**, the most recently
//! entered among equals (Schmidt & Budge's rule; priority is the material's `iris_priority`,
//! default 0, so by default the last medium entered wins). Crossing a surface of a medium
//! that is not the current one on either side is a false interface: no refraction. So water
//! modelled overlapping its glass (glass at a higher priority) refracts at the glass's inner
//! wall both ways, and its own faces inside the glass are ignored. Entering pushes, exiting
//! removes the last occurrence. A path that exits a medium it never entered (open meshes, a
//! camera inside glass) is handled as that-medium-to-current, the best guess; a path in
//! no medium at all that exits one (a camera or a light inside it) learns the media beyond
//! the surface from a probe ray ([`media_beyond`]), so a camera inside a stone inside
//! water meets stone → water, and the segment it ran in that medium
//! ([`segment_medium`]). Depth is bounded by [`MAX_NESTING`]; deeper nesting drops the
//! oldest entry.

use crate::interaction::{CoincidentFaces, SurfaceHit, MAX_COINCIDENT};
use crate::scene::Scene;

/// Deepest nesting tracked.
pub const MAX_NESTING: usize = 8;

/// Most surfaces a probe ray of [`media_beyond`] crosses.
pub const PROBE_HITS: usize = 64;

/// The media a path is inside, innermost last. `Copy`, so each branch gets its own.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct MediumStack {
    ids: [u32; MAX_NESTING],
    priorities: [i32; MAX_NESTING],
    len: u8,
}

impl MediumStack {
    /// The empty stack: the path is in air.
    pub fn new() -> Self {
        Self::default()
    }

    /// The medium the path is in: the highest priority, the latest entered among equals;
    /// `None` for air.
    pub fn current(&self) -> Option<u32> {
        let n = self.len as usize;
        let best = (0..n).max_by_key(|&i| (self.priorities[i], i))?;
        Some(self.ids[best])
    }

    /// The media the path is inside, outermost first.
    pub fn iter(&self) -> impl Iterator<Item = u32> + '_ {
        self.ids[..self.len as usize].iter().copied()
    }

    /// Whether the path is inside material `m`.
    pub fn contains(&self, m: u32) -> bool {
        self.ids[..self.len as usize].contains(&m)
    }

    /// The stack after entering material `m` of priority `priority`.
    pub fn entered(mut self, m: u32, priority: i32) -> Self {
        if self.len as usize == MAX_NESTING {
            self.ids.copy_within(1.., 0);
            self.priorities.copy_within(1.., 0);
            self.len -= 1;
        }
        self.ids[self.len as usize] = m;
        self.priorities[self.len as usize] = priority;
        self.len += 1;
        self
    }

    /// The stack after leaving material `m` (its last occurrence; unchanged if absent).
    pub fn left(mut self, m: u32) -> Self {
        let n = self.len as usize;
        if let Some(i) = self.ids[..n].iter().rposition(|&x| x == m) {
            self.ids.copy_within(i + 1..n, i);
            self.priorities.copy_within(i + 1..n, i);
            // Keep unused slots zero so equality is structural.
            self.ids[n - 1] = 0;
            self.priorities[n - 1] = 0;
            self.len -= 1;
        }
        self
    }
}

/// The two sides of a volumetric interface crossed by a path with stack `stack`: the
/// surfaces crossed at one point are `(material, entering, priority)` — one, or several where
/// touching objects share a face. Returns (n_incident, n_transmitted, the stack on the
/// transmitted side); `ior(id)` gives a material's index, air is 1. The path leaves every
/// medium it exits, then enters every medium it enters, and refracts once with the indices
/// before and after. Overlapping volumes work out: inside glass, entering water gives
/// 1.5 → 1.33, and the glass wall met later inside the water is a false interface.
/// Glass whose inner wall coincides with the water's outer wall gives 1.5 → 1.33 in one
/// step; two touching prisms of one glass give 1.5 → 1.5 (no interface); both faces of a
/// glass sheet thinner than the merge distance, met from outside, are no interface either.
/// A medium exited but never entered (open meshes, a camera inside) is taken as the
/// incident one.
pub fn interface_merged(
    stack: MediumStack,
    crossings: &[(u32, bool, i32)],
    ior: impl Fn(u32) -> f32,
) -> (f32, f32, MediumStack) {
    let ior_of = |id: Option<u32>| id.map_or(1.0, &ior);
    // Both sides of a sheet of `m` thinner than the merge distance, met from outside it:
    // entered and left in one step, so it changes nothing.
    let through = |m: u32| {
        !stack.contains(m)
            && crossings.iter().any(|c| c.0 == m && c.1)
            && crossings.iter().any(|c| c.0 == m && !c.1)
    };
    let kept = || crossings.iter().filter(|c| !through(c.0));
    let unknown_exit = kept().find(|&&(m, entering, _)| !entering && !stack.contains(m));
    let n_i = match unknown_exit {
        Some(&(m, _, _)) => ior(m),
        None => ior_of(stack.current()),
    };
    let mut after = stack;
    for &(m, entering, _) in kept() {
        if !entering {
            after = after.left(m);
        }
    }
    for &(m, entering, priority) in kept() {
        if entering {
            after = after.entered(m, priority);
        }
    }
    (n_i, ior_of(after.current()), after)
}

/// The volumetric interface a path with media `media` crosses at `hit`, with the volumetric
/// surfaces coincident with it ([`Scene::coincident`]) merged in: n_incident,
/// n_transmitted and the media beyond, with `ior(material)` the index of each medium and the
/// materials' `iris_priority` for overlaps. Non-volumetric partners take no part (the caller
/// lets an opaque partner replace the hit instead, see `shading::meet`).
pub fn crossing(
    scene: &Scene,
    hit: &SurfaceHit,
    coincident: &CoincidentFaces,
    media: MediumStack,
    ior: impl Fn(u32) -> f32,
) -> (f32, f32, MediumStack) {
    let priority = |m: u32| scene.materials()[m as usize].desc.priority;
    let mut crossings =
        [(hit.material, hit.front_face, priority(hit.material)); 1 + MAX_COINCIDENT];
    let mut n = 1;
    for c in coincident.iter() {
        if scene.materials()[c.material as usize].is_volume() {
            crossings[n] = (c.material, c.front_face, priority(c.material));
            n += 1;
        }
    }
    // A path in no medium leaving one started inside it: the media it was in are the
    // media beyond the surface and, innermost, the ones it leaves. A medium both entered
    // and left at this interface (a sheet thinner than the merge distance) is passed
    // through, not started in.
    let crossed = &crossings[..n];
    let leaves_unentered = |c: &&(u32, bool, _)| !c.1 && !crossed.iter().any(|d| d.1 && d.0 == c.0);
    let started_inside = media.current().is_none() && crossed.iter().any(|c| leaves_unentered(&c));
    let media = if started_inside {
        crossed
            .iter()
            .filter(leaves_unentered)
            .fold(media_beyond(scene, hit), |s, c| s.entered(c.0, c.2))
    } else {
        media
    };
    interface_merged(media, &crossings[..n], ior)
}

/// The volumetric media containing the point just beyond `hit` on its normal's side, outermost
/// first: a probe ray from there along the normal, each volume whose first face on it is
/// left rather than entered contains the point (closed meshes; the first left is the
/// innermost). At most [`PROBE_HITS`] faces are crossed.
pub fn media_beyond(scene: &Scene, hit: &SurfaceHit) -> MediumStack {
    let mut entered: [u32; PROBE_HITS] = [u32::MAX; PROBE_HITS];
    let mut containing: Vec<u32> = Vec::new();
    let mut ray = hit.spawn_ray(hit.ng);
    for k in 0..PROBE_HITS {
        let Some(h) = scene.intersect(&ray) else {
            break;
        };
        let m = h.material;
        if scene.materials()[m as usize].is_volume() && !entered[..k].contains(&m) {
            if h.front_face {
                entered[k] = m;
            } else if !containing.contains(&m) {
                containing.push(m);
            }
        }
        ray = h.spawn_ray(ray.dir);
    }
    let priority = |m: u32| scene.materials()[m as usize].desc.priority;
    containing
        .iter()
        .rev()
        .fold(MediumStack::new(), |s, &m| s.entered(m, priority(m)))
}

/// The medium a segment ending at `hit` ran in: the path's current one or, for a path in
/// no medium leaving a volume through `hit` (it started inside), that volume.
pub fn segment_medium(scene: &Scene, media: &MediumStack, hit: &SurfaceHit) -> Option<u32> {
    let m = hit.material;
    media
        .current()
        .or_else(|| (!hit.front_face && scene.materials()[m as usize].is_volume()).then_some(m))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interface_indices_for_nested_and_overlapping_volumes() {
        let ior = |m: u32| [1.5f32, 1.33][m as usize];
        let (glass, water) = (0u32, 1u32);
        let air = MediumStack::new();
        // Air → glass.
        let (ni, nt, in_glass) = interface_merged(air, &[(glass, true, 0)], ior);
        assert_eq!((ni, nt), (1.0, 1.5));
        // Inside the glass wall, entering the (overlapping) water: 1.5 → 1.33.
        let (ni, nt, in_water) = interface_merged(in_glass, &[(water, true, 0)], ior);
        assert_eq!((ni, nt), (1.5, 1.33));
        // The glass's inner wall, met inside the water, is a false interface.
        let (ni, nt, s) = interface_merged(in_water, &[(glass, false, 0)], ior);
        assert_eq!((ni, nt), (1.33, 1.33));
        assert_eq!(s.current(), Some(water));
        // Water → air at the free surface.
        let (ni, nt, s) = interface_merged(s, &[(water, false, 0)], ior);
        assert_eq!((ni, nt), (1.33, 1.0));
        assert_eq!(s, MediumStack::new());
        // Exiting glass never entered (camera inside): glass → air.
        assert_eq!(interface_merged(air, &[(glass, false, 0)], ior).0, 1.5);
    }

    #[test]
    fn merged_crossings_refract_once_between_the_outer_media() {
        let ior = |m: u32| [1.5f32, 1.33][m as usize];
        let (glass, water) = (0u32, 1u32);
        let in_glass = MediumStack::new().entered(glass, 0);
        // Glass wall → water through coincident faces: leave glass, enter water.
        let (ni, nt, s) = interface_merged(in_glass, &[(glass, false, 0), (water, true, 0)], ior);
        assert_eq!((ni, nt), (1.5, 1.33));
        assert_eq!(s, MediumStack::new().entered(water, 0));
        // Order of the crossings does not matter.
        let (ni2, nt2, s2) =
            interface_merged(in_glass, &[(water, true, 0), (glass, false, 0)], ior);
        assert_eq!((ni2, nt2, s2), (ni, nt, s));
        // And back: water → glass.
        let (ni, nt, s) = interface_merged(s, &[(water, false, 0), (glass, true, 0)], ior);
        assert_eq!((ni, nt), (1.33, 1.5));
        assert_eq!(s, in_glass);
        // Two touching prisms of the same glass: no interface, still inside glass.
        let (ni, nt, s) = interface_merged(in_glass, &[(glass, false, 0), (glass, true, 0)], ior);
        assert_eq!((ni, nt, s), (1.5, 1.5, in_glass));
        // Both faces of a glass sheet thinner than the merge distance, met from air or from
        // inside water: no interface, and the sheet is not left on the stack.
        let air = MediumStack::new();
        let sheet = [(glass, true, 0), (glass, false, 0)];
        assert_eq!(interface_merged(air, &sheet, ior), (1.0, 1.0, air));
        let in_water = air.entered(water, 0);
        assert_eq!(
            interface_merged(in_water, &sheet, ior),
            (1.33, 1.33, in_water)
        );
        // Exiting glass never entered, into water: 1.5 → 1.33.
        let (ni, nt, _) = interface_merged(
            MediumStack::new(),
            &[(glass, false, 0), (water, true, 0)],
            ior,
        );
        assert_eq!((ni, nt), (1.5, 1.33));
    }

    /// Schmidt & Budge: water (priority 0) modelled overlapping the wall of its glass
    /// (priority 1). Along a ray through the glass: the water's face inside the glass wall is
    /// a false interface, the real glass→water interface is the glass's inner wall, and the
    /// same holds on the way out — whichever order the faces are met in.
    #[test]
    fn priorities_decide_overlaps() {
        let ior = |m: u32| [1.5f32, 1.33][m as usize];
        let (glass, water) = (0u32, 1u32);
        let air = MediumStack::new();
        let (_, _, s) = interface_merged(air, &[(glass, true, 1)], ior);
        // Entering the water inside the glass wall: glass still wins.
        let (ni, nt, s) = interface_merged(s, &[(water, true, 0)], ior);
        assert_eq!((ni, nt, s.current()), (1.5, 1.5, Some(glass)));
        // Leaving the glass at its inner wall: into the water.
        let (ni, nt, s) = interface_merged(s, &[(glass, false, 1)], ior);
        assert_eq!((ni, nt, s.current()), (1.5, 1.33, Some(water)));
        // Far side: entering the glass's inner wall from the water.
        let (ni, nt, s) = interface_merged(s, &[(glass, true, 1)], ior);
        assert_eq!((ni, nt, s.current()), (1.33, 1.5, Some(glass)));
        // The water's face inside the glass wall: false.
        let (ni, nt, s) = interface_merged(s, &[(water, false, 0)], ior);
        assert_eq!((ni, nt), (1.5, 1.5));
        let (ni, nt, s) = interface_merged(s, &[(glass, false, 1)], ior);
        assert_eq!((ni, nt, s), (1.5, 1.0, air));
        // With equal priorities the last medium entered wins instead (the default).
        let (_, _, s) = interface_merged(air, &[(glass, true, 0)], ior);
        let (ni, nt, _) = interface_merged(s, &[(water, true, 0)], ior);
        assert_eq!((ni, nt), (1.5, 1.33));
    }

    #[test]
    fn enter_and_leave_in_any_order() {
        let s = MediumStack::new();
        assert_eq!(s.current(), None);
        let glass = s.entered(1, 0);
        let water = glass.entered(2, 0);
        assert_eq!(water.current(), Some(2));
        // Leaving the glass wall while still in the water (overlapping volumes).
        assert_eq!(water.left(1).current(), Some(2));
        assert_eq!(water.left(2).current(), Some(1));
        assert_eq!(water.left(2).left(1), MediumStack::new());
        // Leaving something never entered changes nothing.
        assert_eq!(glass.left(7), glass);
        // Overflow drops the oldest.
        let mut deep = MediumStack::new();
        for i in 0..(MAX_NESTING as u32 + 2) {
            deep = deep.entered(i, 0);
        }
        assert_eq!(deep.current(), Some(MAX_NESTING as u32 + 1));
        assert!(!deep.contains(0) && !deep.contains(1) && deep.contains(2));
    }
}
