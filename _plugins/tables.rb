# frozen_string_literal: true

# Every table of a page fits the screen it is read on, without losing the column that
# names its rows (styles: "Tables on every screen" in assets/css/main.css).
#
# - Each table sits in a box of its own that scrolls sideways (div.table-wrap; `display:
#   block` on the table itself would do the same but makes some browsers drop the table's
#   semantics for screen readers), inside a div.table-box that draws the shadows at its
#   edges. The box takes focus so that it can be scrolled with the keyboard.
# - Long names in code (`joint_trajectory_controller/JointTrajectoryController`) may
#   break after `/`, `_` and `.` (a <wbr>, which adds nothing to what is copied), so that
#   no table is wider than the page column on a laptop.
# - Each body cell carries its column's name (`data-label`), from the header row.
# - On a phone a table is shown one of two ways, chosen per table:
#   - `table-cards`: each row becomes a small card, its first cell as the card's title and
#     every other cell under its column's name. For tables of sentences, which a phone
#     could only show one word a line.
#   - `table-pinned`: the table scrolls in its box, its first column pinned at the left
#     edge, and a shadow at the edge beyond which more of it lies (assets/js/site.js). For
#     tables of short values (numbers, units), which read best side by side.
#   A page chooses with a kramdown attribute line after the table, `{: .table-cards}` or
#   `{: .table-pinned}`; otherwise a table whose cells average more than CARD_LETTERS
#   letters becomes cards, and any other pins its first column.
require "cgi/escape"

module Sw2simSite
  module Tables
    TABLE = %r{<table\b([^>]*)>(.*?)</table>}m.freeze
    HEADER_ROW = %r{<thead>\s*<tr>(.*?)</tr>}m.freeze
    HEADER_CELL = %r{<th\b[^>]*>(.*?)</th>}m.freeze
    ROW = %r{<tr>(.*?)</tr>}m.freeze
    CELL = %r{<td\b([^>]*)>(.*?)</td>}m.freeze
    CODE = %r{<code\b([^>]*)>(.*?)</code>}m.freeze
    TAG = /<[^>]+>/.freeze
    CARD_LETTERS = 24
    MODES = %w[table-cards table-pinned].freeze

    module_function

    def wrap(html)
      html.gsub(TABLE) do
        match = Regexp.last_match
        attrs = match[1]
        body = match[2]
        labels = body[HEADER_ROW, 1].to_s.scan(HEADER_CELL).map { |(cell)| text(cell) }
        mode = mode(attrs, body, labels)
        table = "<table#{attrs}>#{label_cells(break_code(body), labels)}</table>"
        %(<div class="table-box #{mode}"><div class="table-wrap" tabindex="0">#{table}</div></div>)
      end
    end

    def text(cell)
      CGI.unescapeHTML(cell.gsub(TAG, "")).gsub(INLINE_TEX) { tex_text(Regexp.last_match(1)) }.strip
    end

    # A formula in a header cell (`\(\Phi_i\)`, typeset only once every page is rendered:
    # _plugins/math.rb) as plain text for its column's name on a card: Φᵢ.
    INLINE_TEX = /\\\((.*?)\\\)/.freeze
    GREEK = { "alpha" => "α", "beta" => "β", "gamma" => "γ", "delta" => "δ", "Delta" => "Δ",
              "theta" => "θ", "mu" => "μ", "pi" => "π", "tau" => "τ", "phi" => "φ", "Phi" => "Φ",
              "omega" => "ω", "Omega" => "Ω" }.freeze
    SUBSCRIPT = { "i" => "ᵢ", "o" => "ₒ", "0" => "₀", "1" => "₁", "2" => "₂", "x" => "ₓ" }.freeze

    def tex_text(tex)
      tex.gsub(/\\([A-Za-z]+)/) { GREEK.fetch(Regexp.last_match(1), Regexp.last_match(1)) }
         .gsub(/_\{?([A-Za-z0-9])\}?/) { SUBSCRIPT.fetch(Regexp.last_match(1), "_#{Regexp.last_match(1)}") }
         .delete("{}").strip
    end

    def mode(attrs, body, labels)
      chosen = MODES.find { |name| attrs.match?(/\bclass="[^"]*\b#{name}\b/) }
      return chosen if chosen
      return "table-pinned" if labels.empty?

      cells = body.scan(CELL).map { |(_, cell)| text(cell) }
      average = cells.empty? ? 0 : cells.sum(&:length).fdiv(cells.length)
      average > CARD_LETTERS ? "table-cards" : "table-pinned"
    end

    # Each body cell gets the name of its column (in a row of the body, the Nth <td>).
    def label_cells(body, labels)
      return body if labels.empty?

      body.gsub(ROW) do
        row = Regexp.last_match(1)
        column = -1
        cells = row.gsub(CELL) do
          column += 1
          attrs = Regexp.last_match(1)
          label = labels[column].to_s
          next Regexp.last_match(0) if label.empty? || attrs.include?("data-label=")

          %(<td#{attrs} data-label="#{CGI.escapeHTML(label)}">#{Regexp.last_match(2)}</td>)
        end
        "<tr>#{cells}</tr>"
      end
    end

    # A break opportunity after each `/`, `_` and `.` of a code span (not at its end).
    def break_code(body)
      body.gsub(CODE) do
        attrs = Regexp.last_match(1)
        code = Regexp.last_match(2)
        broken = code.split(/(<[^>]+>)/).map do |piece|
          piece.start_with?("<") ? piece : piece.gsub(%r{([/_.])(?=[^\s/_.])}, "\\1<wbr>")
        end.join
        "<code#{attrs}>#{broken}</code>"
      end
    end
  end
end

Jekyll::Hooks.register [:pages, :documents], :post_convert do |page|
  next unless page.output_ext == ".html"

  page.content = Sw2simSite::Tables.wrap(page.content)
end
