// viewer_main.cpp: the idk-viewer executable (everything else is in idk_viewer_lib so tests can link it).
#include <string>
#include <vector>

#include "viewer/viewer_app.hpp"

int main(int argc, char** argv) {
    return idk::viewer::runViewer(std::vector<std::string>(argv + 1, argv + argc));
}
