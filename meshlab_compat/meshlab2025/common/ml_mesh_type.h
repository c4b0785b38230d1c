#pragma once
// MeshLab 2022.02 and later moved CMeshO from common/ml_mesh_type.h to common/ml_document/cmesh.h.
// This forwarding header is on the include path of the 2025.07 builds only, so the engines'
// `#include <common/ml_mesh_type.h>` compiles unchanged against both SDKs.
#include <common/ml_document/cmesh.h>
