#include "io/read_obj_with_uv.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/errors.h"
#include "io/read_mesh.h"

namespace liftmap {
namespace {

/// A fresh folder for one test's files.
std::filesystem::path folder(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("liftmap_uv_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::create_directories(dir);
  return dir;
}

std::string write(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path.string();
}

/// A tetrahedron with one vt per corner; `faces` are its f lines.
std::string tetrahedron(const std::string& faces) {
  return "mtllib tet.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
         "vt 0 0\nvt 1 0\nvt 0 1\nvt 0.5 0.5 0\nusemtl skin\n" +
         faces;
}

const std::string kFaces = "f 1/1 3/3 2/2\nf 1/1 2/2 4/4\nf 1/1/1 4/4/1 3/3/1\nf -3/-3 -2/-2 -1/-1\n";

std::string error_of(const std::string& path) {
  try {
    read_obj_with_uv(path);
  } catch (const IoError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ReadObjWithUv, ReadsPositionsFacesUvsAndTheMaterialsImage) {
  const auto dir = folder("good");
  write(dir / "tet.mtl", "newmtl other\nmap_Kd other.png\nnewmtl skin\nKd 1 1 1\nmap_Kd -s 1 1 1 skin.png\n");
  const std::string path = write(dir / "tet.obj", tetrahedron(kFaces));
  const TexturedMesh m = read_obj_with_uv(path);
  EXPECT_EQ(m.V, read_mesh(path).V);
  EXPECT_EQ(m.F, read_mesh(path).F) << "the vertex numbering is read_mesh's";
  ASSERT_EQ(m.UV.rows(), 4);
  EXPECT_EQ(m.UV(3, 0), 0.5);
  ASSERT_EQ(m.FT.rows(), 4);
  EXPECT_EQ(m.FT.row(0), Eigen::RowVector3i(0, 2, 1));
  EXPECT_EQ(m.FT.row(3), Eigen::RowVector3i(1, 2, 3)) << "negative indices count back";
  EXPECT_EQ(m.material_file, (dir / "tet.mtl").string());
  EXPECT_EQ(m.texture_path, (dir / "skin.png").string()) << "the used material's map_Kd, its options skipped";
}

TEST(ReadObjWithUv, MissingMaterialFileLeavesNoTexture) {
  const auto dir = folder("no_mtl");
  const TexturedMesh m = read_obj_with_uv(write(dir / "tet.obj", tetrahedron(kFaces)));
  EXPECT_EQ(m.material_file, (dir / "tet.mtl").string());
  EXPECT_TRUE(m.texture_path.empty());
}

TEST(ReadObjWithUv, ErrorsNameTheFileAndLine) {
  const auto dir = folder("bad");
  const auto expect_error = [&](const std::string& name, const std::string& text, const std::string& what) {
    const std::string path = write(dir / (name + ".obj"), text);
    const std::string e = error_of(path);
    EXPECT_NE(e.find(path + ":" + what), std::string::npos) << name << ": " << e;
  };
  // Line 1 is mtllib, 2-5 v, 6-9 vt, 10 usemtl, 11- the faces.
  expect_error("face_without_vt", tetrahedron("f 1/1 3/3 2/2\nf 1 2 4\n"), "12: face corner '1' has no texture");
  expect_error("normal_without_vt", tetrahedron("f 1//1 3//1 2//1\n"), "11: face corner '1//1' has no texture");
  expect_error("vt_out_of_range", tetrahedron("f 1/1 3/3 2/5\n"), "11: face references texture coordinate 5, but 4");
  expect_error("vt_zero", tetrahedron("f 1/0 3/3 2/2\n"), "11: face references texture coordinate 0");
  expect_error("vt_short", "v 0 0 0\nvt 0.5\n", "2: texture coordinate needs 2 numbers");
  expect_error("vt_word", "v 0 0 0\nvt 0.5 half\n", "2: 'half' is not a number");
  expect_error("no_vt", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "4: face before any texture coordinate");
  expect_error("quad", tetrahedron("f 1/1 2/2 3/3 4/4\n"), "11: face has 4 vertices");
  expect_error("vertex_out_of_range", tetrahedron("f 1/1 9/3 2/2\n"), "11: face references vertex 9, but 4");
  EXPECT_NE(error_of((dir / "missing.obj").string()).find("no such file"), std::string::npos);
}

TEST(ReadObjWithUv, MalformedMaterialFileNamesItsLine) {
  const auto dir = folder("bad_mtl");
  write(dir / "tet.mtl", "newmtl skin\nmap_Kd\n");
  const std::string e = error_of(write(dir / "tet.obj", tetrahedron(kFaces)));
  EXPECT_NE(e.find((dir / "tet.mtl").string() + ":2: 'map_Kd' without a file name"), std::string::npos) << e;
}

}  // namespace
}  // namespace liftmap
