// Mass properties of a solid of uniform density bounded by a closed triangle mesh, exactly (up
// to rounding): the polyhedral volume integrals of Mirtich (1996, "Fast and Accurate
// Computation of Polyhedral Mass Properties", J. Graphics Tools 1(2)) as streamlined for
// triangles by Eberly ("Polyhedral Mass Properties (Revisited)", Geometric Tools, 2002); seed
// /work/shared/seeds/002_*, "Mirtich-Eberly Algorithm".
//
// The mesh must bound a solid: closed (every edge shared by exactly two triangles that run
// along it in opposite directions), triangles counter-clockwise seen from outside, none
// degenerate, positive enclosed volume. Vertices not used by any triangle are ignored.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "engine/math.hpp"

namespace rigidlab {

// Vertex indices of a triangle, counting from 0 (messages count from 1, as Lua users do).
using MeshTriangle = std::array<int, 3>;

struct MeshMassProperties {
  double mass = 0.0;            // kg (density · volume)
  Vec3 com = Vec3::Zero();      // m
  Mat3 inertia = Mat3::Zero();  // kg·m², about com, axes of the mesh's frame
  double volume = 0.0;          // m³
};

// Empty when the mesh bounds a solid, otherwise one sentence saying what is wrong and where,
// with vertex and triangle numbers counting from 1: too few vertices or triangles, a
// non-finite vertex, an index out of range, a degenerate triangle, an open edge, an edge shared
// by more than two triangles, inconsistent winding, an inside-out mesh, zero volume.
std::string mesh_problem(const std::vector<Vec3>& vertices,
                         const std::vector<MeshTriangle>& triangles);

// Mass, COM, tensor about the COM and volume of the solid of `density` (kg/m³, finite, > 0)
// bounded by the mesh (vertices in m). Throws std::invalid_argument with mesh_problem's message
// for a mesh that does not bound a solid.
MeshMassProperties inertia_mesh(const std::vector<Vec3>& vertices,
                                const std::vector<MeshTriangle>& triangles,
                                double density = 1.0);

}  // namespace rigidlab
