//! (temporary lead stub, replaced by the helper's store on merge)
use glam::Vec3;

/// A stored photon.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Photon {
    pos: [f32; 3],
    dir: u32,
    power: [f32; 4],
    wi: Vec3,
    flags: u32,
}

impl Photon {
    /// Hero only.
    pub const HERO_ONLY: u32 = 1;
    /// Caustic.
    pub const CAUSTIC: u32 = 2;
    /// New.
    pub fn new(p: Vec3, wi: Vec3, power: [f32; 4], flags: u32) -> Photon {
        Photon {
            pos: p.to_array(),
            dir: 0,
            power,
            wi,
            flags,
        }
    }
    /// Position.
    pub fn position(&self) -> Vec3 {
        Vec3::from_array(self.pos)
    }
    /// Wi.
    pub fn wi(&self) -> Vec3 {
        self.wi
    }
    /// Power.
    pub fn power(&self) -> [f32; 4] {
        self.power
    }
    /// Flags.
    pub fn flags(&self) -> u32 {
        self.flags
    }
}

/// Map.
pub struct PhotonMap {
    photons: Vec<Photon>,
}

impl PhotonMap {
    /// Build.
    pub fn build(photons: Vec<Photon>) -> PhotonMap {
        PhotonMap { photons }
    }
    /// Len.
    pub fn len(&self) -> usize {
        self.photons.len()
    }
    /// Empty.
    pub fn is_empty(&self) -> bool {
        self.photons.is_empty()
    }
    /// Photons.
    pub fn photons(&self) -> &[Photon] {
        &self.photons
    }
    /// Get.
    pub fn get(&self, i: usize) -> &Photon {
        &self.photons[i]
    }
    /// Knn.
    pub fn knn(&self, p: Vec3, k: usize, max_r2: f32, out: &mut Vec<(f32, u32)>) -> f32 {
        out.clear();
        for (i, ph) in self.photons.iter().enumerate() {
            let d2 = ph.position().distance_squared(p);
            if d2 <= max_r2 {
                out.push((d2, i as u32));
            }
        }
        out.sort_by(|a, b| a.0.total_cmp(&b.0));
        out.truncate(k);
        out.last().map_or(0.0, |x| x.0)
    }
    /// Within.
    pub fn for_each_within(&self, p: Vec3, r2: f32, mut f: impl FnMut(&Photon, f32)) {
        for ph in &self.photons {
            let d2 = ph.position().distance_squared(p);
            if d2 <= r2 {
                f(ph, d2)
            }
        }
    }
}

/// Grid.
#[derive(Default)]
pub struct HashGrid {
    pts: Vec<Vec3>,
}

impl HashGrid {
    /// New.
    pub fn new() -> HashGrid {
        HashGrid::default()
    }
    /// Rebuild.
    pub fn rebuild(&mut self, points: &[Photon], _radius: f32) {
        self.pts.clear();
        self.pts.extend(points.iter().map(|p| p.position()));
    }
    /// Within.
    pub fn for_each_within(&self, p: Vec3, r: f32, mut f: impl FnMut(u32, f32)) {
        for (i, q) in self.pts.iter().enumerate() {
            let d2 = q.distance_squared(p);
            if d2 <= r * r {
                f(i as u32, d2)
            }
        }
    }
}
