# frozen_string_literal: true

# Gives every highlighted code block a header line, built into the HTML so it shows
# without scripts:
#
#   - the language (`python`, `bash`, ...), or the file the block shows when the block
#     carries `data-file` (a link when the file is published, e.g. under examples/);
#   - a "Not run here: <reason>" badge when the block carries `data-skip`;
#   - a note that the tests run the block under ROS 1 when it carries `data-ros`;
#   - a note that the tests run the block under ROS 2 when it carries `data-ros2`;
#   - a "Not run here, needs: <what>" badge when it carries `data-ros2-needs` (a command
#     for a machine with ROS 2 Jazzy and Gazebo Sim, which the site's tests do not have).
#
# Both attributes come from a kramdown attribute line right after the closing fence:
#
#     ```python
#     import rospy
#     ```
#     {: data-skip="needs a ROS master and Gazebo"}
#
# (An info string such as ```` ```python skip ```` is not a fence for kramdown: it would
# print as text.) assets/js/site.js adds the copy button to the header.
require "cgi/escape"

module Sw2simSite
  module CodeBlocks
    # kramdown writes `<div class="language-x highlighter-rouge" ...>` with attribute-line
    # attributes in any order, followed by rouge's `<div class="highlight">`.
    BLOCK_OPEN = %r{<div\b([^>]*\bclass="[^"]*\bhighlighter-rouge\b[^"]*"[^>]*)>(\s*<div class="highlight">)}.freeze
    ATTRIBUTE = /([\w:-]+)="([^"]*)"/.freeze
    # A long line scrolls inside its block; a keyboard user can only scroll a box that
    # can take focus.
    PRE_OPEN = '<pre class="highlight">'
    PRE_FOCUSABLE = '<pre class="highlight" tabindex="0">'

    module_function

    def decorate(html, site)
      html.gsub(BLOCK_OPEN) do
        attrs_text = Regexp.last_match(1)
        inner_open = Regexp.last_match(2)
        attrs = attrs_text.scan(ATTRIBUTE).to_h
        "<div#{attrs_text}>#{header(attrs, site)}#{skip_badge(attrs)}#{needs_badge(attrs)}" \
          "#{ros_badge(attrs, site)}#{ros2_badge(attrs, site)}#{inner_open}"
      end.gsub(PRE_OPEN, PRE_FOCUSABLE).gsub(TEXT_BLOCK) do
        "#{Regexp.last_match(1)}#{lines_html(Regexp.last_match(2))}#{Regexp.last_match(3)}"
      end
    end

    # What a command printed (```text) wraps at every width, each line under its own
    # indentation (styles: "Whole output lines" in assets/css/main.css): each line that is
    # not empty becomes a span carrying how far its text is indented (spaces and the
    # characters of a drawn tree), and the newlines stay between the spans, so that what
    # is copied is the block's text as it was.
    TEXT_BLOCK = %r{(<div\b[^>]*\bclass="[^"]*\blanguage-text\b[^>]*>.*?<pre[ ]class="highlight"[^>]*><code>)
                    (.*?)(</code></pre>)}xm.freeze
    INDENT = /\A[ \t│├└─┬┼┐┘┌]*/.freeze

    def lines_html(code)
      code.split("\n", -1).map { |line| line_html(line) }.join("\n")
    end

    # A line of escaped text as an output line; its indentation counted in characters.
    def line_html(line)
      return line if line.empty?

      indent = CGI.unescapeHTML(line.gsub(/<[^>]+>/, ""))[INDENT].length
      %(<span class="code-output-line" style="--indent: #{indent}">#{line}</span>)
    end

    # Attribute values arrive HTML-escaped from kramdown and are written back as they are.
    def header(attrs, site)
      title = if attrs.key?("data-file")
                file_label(attrs["data-file"], site)
              else
                language = attrs["class"][/\blanguage-([\w+#.-]+)/, 1] || "text"
                language = "text" if language == "plaintext"
                %(<span class="code-lang">#{language}</span>)
              end
      %(<div class="code-header">#{title}</div>)
    end

    def file_label(path, site)
      published = Array(site.config["verbatim_dirs"]).any? { |dir| path.start_with?("#{dir}/") } &&
                  File.file?(File.join(site.source, CGI.unescapeHTML(path)))
      label = %(<code class="code-file">#{path}</code>)
      return label unless published

      href = "#{site.baseurl.to_s.chomp("/")}/#{path}"
      %(<a class="code-file-link" href="#{href}" title="Open the whole file">#{label}</a>)
    end

    def skip_badge(attrs)
      return "" unless attrs.key?("data-skip")

      reason = attrs["data-skip"].strip
      detail = reason.empty? ? "" : " #{reason}"
      %(<div class="code-skip"><strong>Not run here:</strong>#{detail}</div>)
    end

    def needs_badge(attrs)
      return "" unless attrs.key?("data-ros2-needs")

      %(<div class="code-skip code-needs"><strong>Not run here, needs:</strong> ) +
        %(#{attrs["data-ros2-needs"].strip}</div>)
    end

    # The page the note links to explains the stand-in the tests run ROS blocks with.
    ROS_PAGE = "/reference/ros-without-gazebo/"

    def ros_badge(attrs, site)
      return "" unless attrs.key?("data-ros")

      href = "#{site.baseurl.to_s.chomp("/")}#{ROS_PAGE}"
      %(<div class="code-ros">Run by the site's tests under ROS 1, with MuJoCo in Gazebo's place ) +
        %((<a href="#{href}">how</a>)</div>)
    end

    # The ROS 2 track's entry page says what stands in for Gazebo Sim here.
    ROS2_PAGE = "/reference/ros1-to-ros2/"

    def ros2_badge(attrs, site)
      return "" unless attrs.key?("data-ros2")

      href = "#{site.baseurl.to_s.chomp("/")}#{ROS2_PAGE}#here-sw2sim-ros2"
      %(<div class="code-ros code-ros2">Run by the site's tests under ROS 2 (rclpy), with MuJoCo in ) +
        %(Gazebo Sim's place (<a href="#{href}">how</a>)</div>)
    end
  end
end

Jekyll::Hooks.register [:pages, :documents], :post_convert do |page|
  next unless page.output_ext == ".html"

  page.content = Sw2simSite::CodeBlocks.decorate(page.content, page.site)
end
