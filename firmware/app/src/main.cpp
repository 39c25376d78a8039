// SPDX-License-Identifier: Apache-2.0
// The probe-controller firmware's one main(): the app (app.hpp) over the board this image is
// built for (the board directory's app_board.hpp names it: TargetBoard). Startup (the board's
// reset handler) has set up memory and the FPU.
#include "app_board.hpp"
#include "palp/app/app.hpp"

int main() {
  static palp::app::TargetBoard board;
  static palp::app::App<palp::app::TargetBoard> app{board};
  app.run();
}
